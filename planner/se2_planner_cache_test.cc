// Se2PlannerCache: the same map, footprint and options give the kept planner; any difference
// a new one, which plans as a planner built directly does; the least recently used goes.

#include "planner/se2_planner_cache.h"

#include <gtest/gtest.h>

#include "planner/test_maps.h"

namespace minenav {
namespace {

using planner_test::Room;

TEST(Se2PlannerCacheTest, TheSameRequestGetsTheKeptPlannerAndAnyDifferenceANewOne) {
  Se2PlannerCache cache(8);
  const std::vector<Segment> room = Room(30.0, 20.0);
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  Se2PlannerOptions options;
  options.clearance = 0.1;
  const auto first = cache.Get(room, miner, options);
  EXPECT_EQ(cache.Get(room, miner, options), first);
  EXPECT_EQ(cache.built(), 1);

  // Each of these differs in one thing: a new planner each, built for exactly what was asked.
  std::vector<Segment> moved = room;
  moved.back().b.x() += 1e-9;
  Se2PlannerOptions wider = options;
  wider.clearance = 0.3;
  Se2PlannerOptions no_reverse = options;
  no_reverse.costs.reverse_factor = 100.0;
  const auto other_map = cache.Get(moved, miner, options);
  const auto other_footprint = cache.Get(room, Footprint::Rectangle(3.3, 9.0), options);
  const auto other_clearance = cache.Get(room, miner, wider);
  const auto other_costs = cache.Get(room, miner, no_reverse);
  EXPECT_EQ(cache.built(), 5);
  for (const auto& p : {other_map, other_footprint, other_clearance, other_costs}) EXPECT_NE(p, first);
  EXPECT_EQ(other_clearance->options().clearance, 0.3);
  EXPECT_EQ(other_costs->options().costs.reverse_factor, 100.0);
  EXPECT_EQ(other_map->map().back().b.x(), moved.back().b.x());
  EXPECT_EQ(cache.Get(room, miner, wider), other_clearance);
  EXPECT_EQ(cache.built(), 5);

  // A kept planner answers as one built directly.
  const Pose2 start(8.0, 10.0, 0.0), goal(22.0, 10.0, 0.0);
  const Se2PlanResult kept = first->Plan(start, goal), direct = Se2Planner(room, miner, options).Plan(start, goal);
  ASSERT_EQ(kept.status, SearchStatus::kFound);
  EXPECT_EQ(kept.cost, direct.cost);
  EXPECT_EQ(kept.path.pieces.size(), direct.path.pieces.size());
}

TEST(Se2PlannerCacheTest, TheLeastRecentlyUsedGoesAndAHeldPlannerStaysValid) {
  Se2PlannerCache cache(2);
  const Footprint miner = Footprint::Rectangle(3.3, 10.0);
  const Se2PlannerOptions options;
  const std::vector<Segment> a = Room(30.0, 20.0), b = Room(31.0, 20.0), c = Room(32.0, 20.0);
  const auto held = cache.Get(a, miner, options);
  cache.Get(b, miner, options);
  cache.Get(a, miner, options);  // a is now the most recent: b goes next
  cache.Get(c, miner, options);
  EXPECT_EQ(cache.size(), 2u);
  EXPECT_EQ(cache.built(), 3);
  EXPECT_EQ(cache.Get(a, miner, options), held);  // kept
  EXPECT_EQ(cache.built(), 3);
  cache.Get(b, miner, options);                   // was evicted: built again, c goes
  EXPECT_EQ(cache.built(), 4);
  cache.Clear();
  EXPECT_EQ(cache.size(), 0u);
  // The planner handed out before the clear still plans.
  EXPECT_EQ(held->Plan(Pose2(8.0, 10.0, 0.0), Pose2(20.0, 10.0, 0.0)).status, SearchStatus::kFound);
}

}  // namespace
}  // namespace minenav
