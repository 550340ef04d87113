#include "planner/state_table.h"

#include <stdexcept>

namespace minenav {

StateTable::StateTable(size_t expected) {
  size_t slots = 16;
  while (slots * 3 / 4 < expected) slots *= 2;
  keys_.assign(slots, kNoKey);
  values_.assign(slots, -1);
  mask_ = slots - 1;
  shift_ = 64;
  for (size_t s = slots; s > 1; s >>= 1) --shift_;
}

void StateTable::Set(uint64_t key, int32_t index) {
  if (key == kNoKey) throw std::invalid_argument("StateTable: the key 2^64 - 1 is reserved");
  for (size_t s = Slot(key);; s = (s + 1) & mask_) {
    if (keys_[s] == key) {
      values_[s] = index;
      return;
    }
    if (keys_[s] == kNoKey) {
      keys_[s] = key;
      values_[s] = index;
      if (++size_ * 4 > keys_.size() * 3) Grow();
      return;
    }
  }
}

void StateTable::Grow() {
  std::vector<uint64_t> keys(keys_.size() * 2, kNoKey);
  std::vector<int32_t> values(keys.size(), -1);
  keys.swap(keys_);
  values.swap(values_);
  mask_ = keys_.size() - 1;
  --shift_;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == kNoKey) continue;
    size_t s = Slot(keys[i]);
    while (keys_[s] != kNoKey) s = (s + 1) & mask_;
    keys_[s] = keys[i];
    values_[s] = values[i];
  }
}

}  // namespace minenav
