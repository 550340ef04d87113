#include "logger/mcap_writer.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "common/file_io.h"

namespace minenav {

namespace {

constexpr char kMagic[] = "\x89MCAP0\r\n";  // 8 bytes
enum Op : uint8_t {
  kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06,
  kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B, kSummaryOffset = 0x0E, kDataEnd = 0x0F,
};

void U8(std::string& s, uint8_t v) { s.push_back(static_cast<char>(v)); }
void U16(std::string& s, uint16_t v) {
  for (int i = 0; i < 2; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void U32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void U64(std::string& s, uint64_t v) {
  for (int i = 0; i < 8; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void Str(std::string& s, std::string_view v) {
  U32(s, static_cast<uint32_t>(v.size()));
  s.append(v);
}
std::string Record(uint8_t op, const std::string& body) {
  std::string r;
  U8(r, op);
  U64(r, body.size());
  r += body;
  return r;
}

}  // namespace

McapWriter::McapWriter(const std::string& path, size_t chunk_bytes, std::string profile, std::string library)
    : path_(path), partial_(path + ".partial"), chunk_bytes_(chunk_bytes) {
  file_ = std::fopen(partial_.c_str(), "wb");
  if (!file_) throw InputError(path + ": cannot create");
  Write(std::string_view(kMagic, 8));
  std::string header;
  Str(header, profile);
  Str(header, library);
  Write(Record(kHeader, header));
}

McapWriter::~McapWriter() {
  if (file_) {
    std::fclose(file_);
    std::remove(partial_.c_str());
  }
}

void McapWriter::Write(std::string_view bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw std::runtime_error(partial_ + ": write failed (disk full?)");
  position_ += bytes.size();
}

uint16_t McapWriter::AddSchema(const std::string& name, const std::string& encoding, std::string_view data) {
  const uint16_t id = next_schema_++;
  std::string body;
  U16(body, id);
  Str(body, name);
  Str(body, encoding);
  Str(body, data);
  const std::string record = Record(kSchema, body);
  schemas_ += record;
  // Before the messages that use it: in the chunk, so a streaming reader meets it first.
  chunk_records_ += record;
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding) {
  const uint16_t id = next_channel_++;
  std::string body;
  U16(body, id);
  U16(body, schema_id);
  Str(body, topic);
  Str(body, message_encoding);
  U32(body, 0);  // metadata: an empty map
  const std::string record = Record(kChannel, body);
  channels_ += record;
  chunk_records_ += record;
  return id;
}

void McapWriter::AddMessage(uint16_t channel_id, uint64_t log_time, uint64_t publish_time, std::string_view data) {
  if (chunk_index_.empty()) {
    chunk_start_ = chunk_end_ = log_time;
  } else {
    chunk_start_ = std::min(chunk_start_, log_time);
    chunk_end_ = std::max(chunk_end_, log_time);
  }
  if (message_count_ == 0) {
    first_time_ = last_time_ = log_time;
  } else {
    first_time_ = std::min(first_time_, log_time);
    last_time_ = std::max(last_time_, log_time);
  }
  std::string body;
  U16(body, channel_id);
  U32(body, sequence_[channel_id]++);
  U64(body, log_time);
  U64(body, publish_time);
  body.append(data);
  chunk_index_[channel_id].emplace_back(log_time, chunk_records_.size());
  chunk_records_ += Record(kMessage, body);
  ++message_count_;
  ++channel_counts_[channel_id];
  if (chunk_records_.size() >= chunk_bytes_) FlushChunk();
}

void McapWriter::FlushChunk() {
  if (chunk_records_.empty()) return;
  ChunkIndex index{};
  index.start_time = chunk_index_.empty() ? 0 : chunk_start_;
  index.end_time = chunk_index_.empty() ? 0 : chunk_end_;
  index.offset = position_;
  std::string body;
  U64(body, index.start_time);
  U64(body, index.end_time);
  U64(body, chunk_records_.size());
  U32(body, 0);  // uncompressed CRC: not computed
  Str(body, "");  // no compression
  U64(body, chunk_records_.size());
  body += chunk_records_;
  Write(Record(kChunk, body));
  index.length = position_ - index.offset;
  index.records_size = chunk_records_.size();
  const uint64_t indexes_start = position_;
  for (const auto& [channel, entries] : chunk_index_) {
    std::string mi;
    U16(mi, channel);
    U32(mi, static_cast<uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) {
      U64(mi, time);
      U64(mi, offset);
    }
    index.message_index_offsets[channel] = position_;
    Write(Record(kMessageIndex, mi));
  }
  index.message_index_length = position_ - indexes_start;
  chunks_.push_back(index);
  chunk_records_.clear();
  chunk_index_.clear();
}

void McapWriter::Close() {
  if (closed_) return;
  FlushChunk();
  std::string data_end;
  U32(data_end, 0);  // data section CRC: not computed
  Write(Record(kDataEnd, data_end));

  // The summary: each group's offset for the Summary Offset records.
  const uint64_t summary_start = position_;
  struct Group {
    uint8_t op;
    uint64_t start, length;
  };
  std::vector<Group> groups;
  const auto group = [&](uint8_t op, const std::string& records) {
    if (records.empty()) return;
    groups.push_back({op, position_, records.size()});
    Write(records);
  };
  group(kSchema, schemas_);
  group(kChannel, channels_);
  std::string stats;
  U64(stats, message_count_);
  U16(stats, static_cast<uint16_t>(next_schema_ - 1));
  U32(stats, next_channel_);
  U32(stats, 0);  // attachments
  U32(stats, 0);  // metadata
  U32(stats, static_cast<uint32_t>(chunks_.size()));
  U64(stats, message_count_ ? first_time_ : 0);
  U64(stats, message_count_ ? last_time_ : 0);
  U32(stats, static_cast<uint32_t>(channel_counts_.size() * 10));
  for (const auto& [channel, count] : channel_counts_) {
    U16(stats, channel);
    U64(stats, count);
  }
  group(kStatistics, Record(kStatistics, stats));
  std::string chunk_indexes;
  for (const ChunkIndex& c : chunks_) {
    std::string b;
    U64(b, c.start_time);
    U64(b, c.end_time);
    U64(b, c.offset);
    U64(b, c.length);
    U32(b, static_cast<uint32_t>(c.message_index_offsets.size() * 10));
    for (const auto& [channel, offset] : c.message_index_offsets) {
      U16(b, channel);
      U64(b, offset);
    }
    U64(b, c.message_index_length);
    Str(b, "");
    U64(b, c.records_size);  // compressed size = uncompressed size
    U64(b, c.records_size);
    chunk_indexes += Record(kChunkIndex, b);
  }
  group(kChunkIndex, chunk_indexes);
  const uint64_t summary_offset_start = position_;
  for (const Group& g : groups) {
    std::string b;
    U8(b, g.op);
    U64(b, g.start);
    U64(b, g.length);
    Write(Record(kSummaryOffset, b));
  }
  std::string footer;
  U64(footer, summary_start);
  U64(footer, summary_offset_start);
  U32(footer, 0);  // summary CRC: not computed
  Write(Record(kFooter, footer));
  Write(std::string_view(kMagic, 8));
  if (std::fclose(file_) != 0) {
    file_ = nullptr;
    throw std::runtime_error(partial_ + ": close failed");
  }
  file_ = nullptr;
  if (std::rename(partial_.c_str(), path_.c_str()) != 0) throw std::runtime_error(path_ + ": cannot rename from .partial");
  closed_ = true;
}

}  // namespace minenav
