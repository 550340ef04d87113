#pragma once
// The visited states of the SE(2) search (se2_planner.h "storage"): from a state's cell key
// (its x, y and heading cells packed in 64 bits) to the index of the best node found there.
// Open addressing with linear probing over two flat arrays (8-byte keys, 4-byte indices),
// doubled when 3/4 full: 16 to 24 bytes a state and no allocation per insert, where
// std::unordered_map takes a heap node of 32 bytes and a bucket pointer (about 40 bytes)
// and an allocation for every state.

#include <cstddef>
#include <cstdint>
#include <vector>

namespace minenav {

class StateTable {
 public:
  // The one key no state has (the search's keys leave the top bits of the heading field 0).
  static constexpr uint64_t kNoKey = ~uint64_t{0};

  // Room for `expected` states before the first doubling.
  explicit StateTable(size_t expected = 1024);

  // The index stored for `key`, or -1.
  int32_t Find(uint64_t key) const {
    for (size_t s = Slot(key);; s = (s + 1) & mask_) {
      if (keys_[s] == key) return values_[s];
      if (keys_[s] == kNoKey) return -1;
    }
  }
  // Stores `index` for `key`, replacing what was stored. `key` must not be kNoKey.
  void Set(uint64_t key, int32_t index);

  size_t size() const { return size_; }
  // Bytes of the table's arrays.
  size_t bytes() const { return keys_.capacity() * sizeof(uint64_t) + values_.capacity() * sizeof(int32_t); }

 private:
  // Fibonacci hashing: the key times 2^64 / golden ratio, its top bits (the cell keys differ
  // in their low bits of x, y and heading; the product spreads them over the top).
  size_t Slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  void Grow();

  std::vector<uint64_t> keys_;
  std::vector<int32_t> values_;
  size_t mask_ = 0;
  int shift_ = 64;
  size_t size_ = 0;
};

}  // namespace minenav
