#pragma once
// Hostile input for the regression tests of issue 11: LCM payloads whose array counts
// lie, built byte by byte, and LCM event logs written byte by byte (so a test can put a
// corrupt header or corrupt bytes exactly where it wants them).
//
// The LCM wire format (big-endian): an 8-byte fingerprint (T::getHash()) for the
// top-level type, then the fields in .lcm order; a string is an int32 length counting
// the NUL, then the bytes and the NUL; nested structs carry no fingerprint; an array is
// its elements, its length being an earlier field. Every payload here is the generated
// encode() of a valid message with empty arrays whose count field is then patched, so
// the payload is short: a decoder that trusts the count either allocates `count`
// elements before it notices (gigabytes for 2^28 and more) or, for counts in
// [2^29, 2^31), overflows `sizeof(element) * count` in LCM 1.3.1's __T_decode_array,
// passes its bounds check and reads past the buffer.
//
// Never decode these payloads in the test process itself: that is the crash under test.

#include <cstdint>
#include <string>
#include <vector>

#include "common/node/conversions.h"

namespace minenav::testing {

inline constexpr int32_t kCount2p24 = int32_t{1} << 24;
inline constexpr int32_t kCount2p26 = int32_t{1} << 26;
inline constexpr int32_t kCount2p28 = int32_t{1} << 28;
inline constexpr int32_t kCount2p29 = int32_t{1} << 29;
inline constexpr int32_t kCountMax = INT32_MAX;

// Big-endian int32 at `offset` (throws std::out_of_range past the end).
void PutInt32BigEndian(std::vector<uint8_t>* bytes, size_t offset, int32_t value);
int32_t GetInt32BigEndian(const std::vector<uint8_t>& bytes, size_t offset);

// ladar_scan_t, sensor_id "typhoon", no readings, with the two count fields set to the
// given values: 92 bytes. num_ranges is at size - 8, num_intensities at size - 4.
std::vector<uint8_t> ScanWithCounts(int32_t num_ranges, int32_t num_intensities, int64_t utime = 1'700'000'000'000'000,
                                    int64_t scan_id = 0);
inline constexpr size_t kScanNumRangesFromEnd = 8;
inline constexpr size_t kScanNumIntensitiesFromEnd = 4;

// contour_map_t (ENCODING_PLAIN) holding one contour with no points whose num_points says
// `num_points`: 54 bytes. num_points is at byte kContourNumPointsOffset.
std::vector<uint8_t> ContourMapWithPointCount(int32_t num_points, int64_t version = 7);
inline constexpr size_t kContourNumPointsOffset = 8 + 8 + 8 + 4 + 4 + 8 + 1;  // hash utime version num_scans num_contours id closed

// contour_map_t (ENCODING_PLAIN) with no contours whose num_contours says `num_contours`:
// 41 bytes. num_contours is at byte kContourMapNumContoursOffset.
std::vector<uint8_t> ContourMapWithContourCount(int32_t num_contours, int64_t version = 7);
inline constexpr size_t kContourMapNumContoursOffset = 8 + 8 + 8 + 4;  // hash utime version num_scans

// contour_map_t (ENCODING_PLAIN, no contours) with an empty payload whose payload_size
// says `payload_size`: 41 bytes; payload_size is the last 4 bytes.
std::vector<uint8_t> ContourMapWithPayloadSize(int32_t payload_size, int64_t version = 7);

// contour_map_t with encoding ENCODING_ZLIB whose payload is the zlib deflate of `inner`
// (an encoded contour_map_t, fingerprint included) and uncompressed_size its size. For
// inner = ContourMapWithPointCount(2^29) it is the 75-byte packet of issue 11.
std::vector<uint8_t> CompressedContourMap(const std::vector<uint8_t>& inner, int64_t version = 7);

// line_map_t, name "x", no segments, whose num_segments says `num_segments`: 34 bytes;
// num_segments is the last 4 bytes.
std::vector<uint8_t> LineMapWithSegmentCount(int32_t num_segments, int64_t version = 7);

// An LCM event log written byte by byte. One event (big-endian): uint32 magic 0xEDA1DA01,
// int64 eventnum, int64 timestamp, int32 channel length, int32 data length, the channel
// (no NUL), the data. Events are numbered from 0 like lcm-logger's.
class RawLog {
 public:
  // Appends an event; returns its byte offset in the file.
  int64_t Add(const std::string& channel, int64_t timestamp, const std::vector<uint8_t>& data);
  // Appends a generated LCM message stamped with its utime.
  template <typename T>
  int64_t AddMessage(const std::string& channel, const T& msg) {
    return Add(channel, msg.utime, EncodeMessage(msg));
  }
  // Appends an event header that claims `declared_data_length` bytes of data, followed by
  // `data` (which may be shorter); returns its byte offset.
  int64_t AddHeader(const std::string& channel, int64_t timestamp, int32_t declared_data_length,
                    const std::vector<uint8_t>& data);
  // Overwrites bytes from `offset` on (must lie inside the log).
  void Overwrite(int64_t offset, const std::vector<uint8_t>& bytes);

  const std::vector<uint8_t>& bytes() const { return bytes_; }
  int64_t size() const { return static_cast<int64_t>(bytes_.size()); }
  // Byte offset of each event added, in order.
  const std::vector<int64_t>& event_offsets() const { return offsets_; }
  // Writes the log to `path` (throws std::runtime_error on failure).
  void Save(const std::string& path) const;

 private:
  std::vector<uint8_t> bytes_;
  std::vector<int64_t> offsets_;
  int64_t next_eventnum_ = 0;
};

// `n` bytes of a fixed pseudo-random sequence (the same for the same seed).
std::vector<uint8_t> PseudoRandomBytes(size_t n, unsigned seed);

}  // namespace minenav::testing
