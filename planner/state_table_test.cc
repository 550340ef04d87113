// StateTable against std::unordered_map: random keys of the search's shape (x and y cells of
// 21 bits, a heading below 720), lookups of absent keys, overwrites, growth from the
// smallest table through many doublings.

#include "planner/state_table.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <unordered_map>

namespace minenav {
namespace {

TEST(StateTableTest, StoresAndFindsWhatAnUnorderedMapDoesThroughEveryDoubling) {
  std::mt19937_64 rng(5);
  // Keys from a small window (many repeats, as a search revisits cells) and from anywhere.
  const auto key = [&](bool near) {
    const uint64_t mask = near ? 0x3F : 0x1FFFFF;
    return ((rng() & mask) << 42) | ((rng() & mask) << 21) | (rng() % 720);
  };
  StateTable table(1);
  std::unordered_map<uint64_t, int32_t> truth;
  for (int32_t i = 0; i < 200000; ++i) {
    const uint64_t k = key(i % 2 == 0);
    table.Set(k, i);
    truth[k] = i;
    if (i % 997 == 0) {
      const uint64_t probe = key(i % 3 == 0);
      const auto it = truth.find(probe);
      ASSERT_EQ(table.Find(probe), it == truth.end() ? -1 : it->second);
    }
  }
  ASSERT_EQ(table.size(), truth.size());
  for (const auto& [k, v] : truth) ASSERT_EQ(table.Find(k), v);
  // At most 3/4 full, so at most 12 / 0.75 = 16 bytes a state plus the doubling's slack.
  EXPECT_LE(static_cast<double>(table.bytes()), 2.0 * 16.0 * static_cast<double>(truth.size()));
  EXPECT_GE(static_cast<double>(table.bytes()), 12.0 * static_cast<double>(truth.size()) / 0.75);
}

TEST(StateTableTest, TheReservedKeyIsRefused) {
  StateTable table;
  EXPECT_THROW(table.Set(StateTable::kNoKey, 1), std::invalid_argument);
  EXPECT_EQ(table.Find(12345), -1);
  EXPECT_EQ(table.size(), 0u);
}

}  // namespace
}  // namespace minenav
