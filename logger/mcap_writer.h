#pragma once
// A writer of MCAP files (mcap.dev/spec, format version 0), the container Foxglove and
// Lichtblick open: magic, Header, Schema and Channel records, Messages in uncompressed Chunks
// each followed by its Message Indexes, Data End, then a summary (Schemas, Channels,
// Statistics, Chunk Indexes, Summary Offsets), the Footer and the magic again. CRCs are
// written as 0, which the spec defines as "not computed". No compression: a JSON log
// compresses well on disk by other means, and readers need no codec.
//
// Written to PATH.partial and renamed by Close() (DESIGN.md, file contracts).

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace minenav {

class McapWriter {
 public:
  static constexpr size_t kChunkBytes = 1 << 20;  // default largest chunk

  // Throws InputError when the file cannot be created. profile: "" (none).
  // chunk_bytes: largest chunk (bytes of records) before a new one starts.
  explicit McapWriter(const std::string& path, size_t chunk_bytes = kChunkBytes, std::string profile = "",
                      std::string library = "minenav log_tool");
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // Returns the schema id (1, 2, ...). encoding e.g. "jsonschema".
  uint16_t AddSchema(const std::string& name, const std::string& encoding, std::string_view data);
  // Returns the channel id (0, 1, ...). message_encoding e.g. "json".
  uint16_t AddChannel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding);
  // log_time and publish_time in ns. Throws std::runtime_error when a write fails.
  void AddMessage(uint16_t channel_id, uint64_t log_time, uint64_t publish_time, std::string_view data);
  // Writes the last chunk, the summary and the footer, and renames PATH.partial to PATH.
  void Close();

  uint64_t messages() const { return message_count_; }


 private:
  struct ChunkIndex {
    uint64_t start_time, end_time, offset, length, message_index_length, records_size;
    std::map<uint16_t, uint64_t> message_index_offsets;
  };
  void Write(std::string_view bytes);
  void FlushChunk();

  std::string path_, partial_;
  size_t chunk_bytes_;
  std::FILE* file_ = nullptr;
  uint64_t position_ = 0;
  std::string schemas_, channels_;  // the records, kept for the summary
  uint16_t next_schema_ = 1, next_channel_ = 0;
  // The open chunk.
  std::string chunk_records_;
  uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;  // channel -> (time, offset)
  std::vector<ChunkIndex> chunks_;
  uint64_t message_count_ = 0, first_time_ = 0, last_time_ = 0;
  std::map<uint16_t, uint64_t> channel_counts_;
  std::map<uint16_t, uint32_t> sequence_;
  bool closed_ = false;
};

}  // namespace minenav
