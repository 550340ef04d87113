#include "tests/hostile_messages.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "minenav/contour_map_t.hpp"
#include "minenav/contour_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"

namespace minenav::testing {

namespace {

constexpr uint32_t kEventMagic = 0xEDA1DA01u;

void AppendBigEndian(std::vector<uint8_t>* out, uint64_t value, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) out->push_back(static_cast<uint8_t>((value >> (8 * i)) & 0xffu));
}

contour_map_t EmptyContourMap(int64_t version) {
  contour_map_t m{};
  m.utime = 1'700'000'000'000'000;
  m.version = version;
  m.num_scans = 1;
  m.num_contours = 0;
  m.encoding = contour_map_t::ENCODING_PLAIN;
  m.uncompressed_size = 0;
  m.payload_size = 0;
  return m;
}

}  // namespace

void PutInt32BigEndian(std::vector<uint8_t>* bytes, size_t offset, int32_t value) {
  if (offset + 4 > bytes->size()) throw std::out_of_range("PutInt32BigEndian: offset past the end");
  const auto v = static_cast<uint32_t>(value);
  for (size_t i = 0; i < 4; ++i) (*bytes)[offset + i] = static_cast<uint8_t>((v >> (8 * (3 - i))) & 0xffu);
}

int32_t GetInt32BigEndian(const std::vector<uint8_t>& bytes, size_t offset) {
  if (offset + 4 > bytes.size()) throw std::out_of_range("GetInt32BigEndian: offset past the end");
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = (v << 8) | bytes[offset + i];
  return static_cast<int32_t>(v);
}

std::vector<uint8_t> ScanWithCounts(int32_t num_ranges, int32_t num_intensities, int64_t utime, int64_t scan_id) {
  ladar_scan_t m{};
  m.utime = utime;
  m.scan_id = scan_id;
  m.sensor_id = "typhoon";
  m.start_angle = -3.14159f;
  m.angle_step = 0.00306796f;
  m.min_range = 0.5f;
  m.max_range = 40.0f;
  m.num_ranges = 0;
  m.num_intensities = 0;
  std::vector<uint8_t> bytes = EncodeMessage(m);
  PutInt32BigEndian(&bytes, bytes.size() - kScanNumRangesFromEnd, num_ranges);
  PutInt32BigEndian(&bytes, bytes.size() - kScanNumIntensitiesFromEnd, num_intensities);
  return bytes;
}

std::vector<uint8_t> ContourMapWithPointCount(int32_t num_points, int64_t version) {
  contour_map_t m = EmptyContourMap(version);
  contour_t c{};
  c.id = 3;
  c.closed = false;
  c.num_points = 0;
  m.contours.push_back(c);
  m.num_contours = 1;
  std::vector<uint8_t> bytes = EncodeMessage(m);
  PutInt32BigEndian(&bytes, kContourNumPointsOffset, num_points);
  return bytes;
}

std::vector<uint8_t> ContourMapWithContourCount(int32_t num_contours, int64_t version) {
  std::vector<uint8_t> bytes = EncodeMessage(EmptyContourMap(version));
  PutInt32BigEndian(&bytes, kContourMapNumContoursOffset, num_contours);
  return bytes;
}

std::vector<uint8_t> ContourMapWithPayloadSize(int32_t payload_size, int64_t version) {
  std::vector<uint8_t> bytes = EncodeMessage(EmptyContourMap(version));
  PutInt32BigEndian(&bytes, bytes.size() - 4, payload_size);
  return bytes;
}

std::vector<uint8_t> CompressedContourMap(const std::vector<uint8_t>& inner, int64_t version) {
  uLongf size = compressBound(static_cast<uLong>(inner.size()));
  std::vector<uint8_t> packed(size);
  if (compress2(packed.data(), &size, inner.data(), static_cast<uLong>(inner.size()), Z_BEST_COMPRESSION) != Z_OK)
    throw std::runtime_error("CompressedContourMap: compress2 failed");
  packed.resize(size);
  contour_map_t m = EmptyContourMap(version);
  m.encoding = contour_map_t::ENCODING_ZLIB;
  m.uncompressed_size = static_cast<int32_t>(inner.size());
  m.payload_size = static_cast<int32_t>(packed.size());
  m.payload = packed;
  return EncodeMessage(m);
}

std::vector<uint8_t> LineMapWithSegmentCount(int32_t num_segments, int64_t version) {
  line_map_t m{};
  m.utime = 1'700'000'000'000'000;
  m.version = version;
  m.name = "x";
  m.num_segments = 0;
  std::vector<uint8_t> bytes = EncodeMessage(m);
  PutInt32BigEndian(&bytes, bytes.size() - 4, num_segments);
  return bytes;
}

int64_t RawLog::Add(const std::string& channel, int64_t timestamp, const std::vector<uint8_t>& data) {
  return AddHeader(channel, timestamp, static_cast<int32_t>(data.size()), data);
}

int64_t RawLog::AddHeader(const std::string& channel, int64_t timestamp, int32_t declared_data_length,
                          const std::vector<uint8_t>& data) {
  const int64_t offset = size();
  AppendBigEndian(&bytes_, kEventMagic, 4);
  AppendBigEndian(&bytes_, static_cast<uint64_t>(next_eventnum_++), 8);
  AppendBigEndian(&bytes_, static_cast<uint64_t>(timestamp), 8);
  AppendBigEndian(&bytes_, static_cast<uint32_t>(channel.size()), 4);
  AppendBigEndian(&bytes_, static_cast<uint32_t>(declared_data_length), 4);
  bytes_.insert(bytes_.end(), channel.begin(), channel.end());
  bytes_.insert(bytes_.end(), data.begin(), data.end());
  offsets_.push_back(offset);
  return offset;
}

void RawLog::Overwrite(int64_t offset, const std::vector<uint8_t>& bytes) {
  if (offset < 0 || offset + static_cast<int64_t>(bytes.size()) > size())
    throw std::out_of_range("RawLog::Overwrite: outside the log");
  std::copy(bytes.begin(), bytes.end(), bytes_.begin() + offset);
}

void RawLog::Save(const std::string& path) const {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error("cannot create " + path);
  const bool ok = std::fwrite(bytes_.data(), 1, bytes_.size(), f) == bytes_.size();
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("cannot write " + path);
}

std::vector<uint8_t> PseudoRandomBytes(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<uint8_t> out(n);
  for (uint8_t& b : out) b = static_cast<uint8_t>(rng() & 0xffu);
  return out;
}

}  // namespace minenav::testing
