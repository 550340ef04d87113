#include "sim/changing_world.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sim/world.h"

namespace minenav {
namespace {

using Vec = Eigen::Vector2d;

double Length(const std::vector<WallSample>& samples, double step, bool hidden_only = false) {
  double n = 0;
  for (const WallSample& s : samples) n += (!hidden_only || s.hidden) ? 1.0 : 0.0;
  return n * step;
}

// Length of the samples lying on `wall` (within 1 mm).
double LengthOn(const std::vector<WallSample>& samples, const Segment& wall, double step) {
  double n = 0;
  for (const WallSample& s : samples) n += PointToSegmentDistance(s.point, wall) < 1e-3 ? 1.0 : 0.0;
  return n * step;
}

TEST(ChangingWorld, SeesWallPointAgainstGeometry) {
  const std::vector<Segment> world = {Segment(0, 0, 10, 0), Segment(4, -1, 6, -1)};
  EXPECT_TRUE(SeesWallPoint(world, Vec(5, 5), Vec(5, 0), 20.0, 0.35));
  // Behind another wall: the ray hits (5, 0) first.
  EXPECT_FALSE(SeesWallPoint(world, Vec(5, 5), Vec(5, -1), 20.0, 0.35));
  // Out of range.
  EXPECT_FALSE(SeesWallPoint(world, Vec(5, 5), Vec(5, 0), 4.0, 0.35));
  // Glancing: the ray meets the wall at atan(0.5 / 9) = 3.2 degrees < 20 degrees.
  EXPECT_FALSE(SeesWallPoint(world, Vec(0, 0.5), Vec(9, 0), 20.0, 0.35));
  EXPECT_TRUE(SeesWallPoint(world, Vec(0, 0.5), Vec(9, 0), 20.0, 0.0));
}

TEST(ChangingWorld, EveryStationIsInFreeSpaceOfItsWorld) {
  for (const ChangingWorldScenario& sc : AllChangingWorldScenarios()) {
    ASSERT_FALSE(sc.stations.empty()) << sc.name;
    for (const Station& st : sc.stations) {
      ASSERT_GE(st.world, 0) << sc.name;
      ASSERT_LT(st.world, static_cast<int>(sc.worlds.size())) << sc.name;
      const auto& world = sc.worlds[static_cast<size_t>(st.world)];
      // Every ray from a free station hits a wall (the worlds are closed) farther than 0.5 m.
      for (int k = 0; k < 72; ++k) {
        const auto hit = CastRay(st.pose.translation(), k * 2.0 * M_PI / 72.0, world, 60.0);
        ASSERT_TRUE(hit) << sc.name << " station at " << st.pose.x << ", " << st.pose.y;
        EXPECT_GT(hit->range, 0.5) << sc.name;
      }
      // And it is outside every pillar and object: on the same side of the walls as the
      // first station of the same world is (World::SameSpace counts wall crossings).
      const World w(world);
      const Station& first = *std::find_if(sc.stations.begin(), sc.stations.end(),
                                           [&](const Station& s) { return s.world == st.world; });
      EXPECT_TRUE(w.SameSpace(st.pose.translation(), first.pose.translation()))
          << sc.name << " station at " << st.pose.x << ", " << st.pose.y;
    }
    for (const ScenarioCheck& c : sc.checks) {
      EXPECT_EQ(sc.stations[static_cast<size_t>(c.after_station)].world, c.world) << sc.name;
      EXPECT_GT(Length(c.must_appear, sc.sample_step), 30.0) << sc.name << ": " << c.label;
      EXPECT_GE(Length(c.must_stay, sc.sample_step), Length(c.must_appear, sc.sample_step)) << sc.name;
    }
  }
}

TEST(ChangingWorld, DoorsOpenJudgesTheLeavesAndTheRoomBeyond) {
  const ChangingWorldScenario sc = DoorsOpenScenario();
  ASSERT_EQ(sc.checks.size(), 1u);
  const ScenarioCheck& c = sc.checks[0];
  // Both leaves (2 m in all) were seen closed and are seen through once open; nothing else
  // disappeared.
  EXPECT_NEAR(LengthOn(c.must_go, Segment(20, 4.5, 20, 6.5), sc.sample_step), 2.0, 0.11);
  EXPECT_NEAR(Length(c.must_go, sc.sample_step), 2.0, 0.11);
  // Room B's far wall (x = 32) is seen through the doorway only in the new world.
  EXPECT_GT(LengthOn(c.must_appear, Segment(32, 0, 32, 12), sc.sample_step), 2.0);
}

TEST(ChangingWorld, DoorClosedHidesTheRoomBeyond) {
  const ChangingWorldScenario sc = DoorClosedScenario();
  const ScenarioCheck& c = sc.checks.at(0);
  EXPECT_EQ(c.must_go.size(), 0u);  // nothing disappeared
  EXPECT_NEAR(LengthOn(c.must_appear, Segment(20, 4.5, 20, 6.5), sc.sample_step), 2.0, 0.11);
  // Room B's far wall, seen through the open door earlier, is hidden now and must stay.
  const Segment far_wall(32, 0, 32, 12);
  double hidden = 0;
  for (const WallSample& s : c.must_stay)
    if (PointToSegmentDistance(s.point, far_wall) < 1e-3 && s.hidden) hidden += sc.sample_step;
  EXPECT_GT(hidden, 2.0);
}

TEST(ChangingWorld, VendingMachineHidesTheWallBehindAndThenGoes) {
  const ChangingWorldScenario sc = VendingMachineScenario();
  ASSERT_EQ(sc.checks.size(), 2u);
  const ScenarioCheck& placed = sc.checks[0];
  const ScenarioCheck& removed = sc.checks[1];
  const Segment behind(11.0, 0.0, 12.4, 0.0);
  EXPECT_EQ(placed.must_go.size(), 0u);
  // The wall behind the box (1.4 m) was seen before and is hidden: all of it must stay.
  double hidden_behind = 0;
  for (const WallSample& s : placed.must_stay)
    if (PointToSegmentDistance(s.point, behind) < 1e-3 && s.hidden) hidden_behind += sc.sample_step;
  EXPECT_NEAR(hidden_behind, 1.4, 0.11);
  // All three faces are seen (front 1 m, sides 0.82 m each).
  EXPECT_NEAR(LengthOn(placed.must_appear, Segment(11.2, 0.8, 12.2, 0.8), sc.sample_step), 1.0, 0.06);
  EXPECT_GT(LengthOn(placed.must_appear, Segment(11.0, 0.0, 11.2, 0.8), sc.sample_step), 0.4);
  EXPECT_GT(LengthOn(placed.must_appear, Segment(12.2, 0.8, 12.4, 0.0), sc.sample_step), 0.4);
  // Once it is gone, the front face must go and the wall behind is seen again.
  EXPECT_NEAR(LengthOn(removed.must_go, Segment(11.2, 0.8, 12.2, 0.8), sc.sample_step), 1.0, 0.06);
  EXPECT_NEAR(LengthOn(removed.must_appear, behind, sc.sample_step), 1.4, 0.11);
  EXPECT_LT(Length(removed.must_go, sc.sample_step), 2.7);
}

TEST(ChangingWorld, ParkedEquipmentAndCoalFace) {
  const ChangingWorldScenario parked = ParkedEquipmentScenario();
  // The machine's perimeter is 17 m; the stations saw most of it and see through it later.
  EXPECT_GT(Length(parked.checks.at(0).must_go, parked.sample_step), 8.0);
  EXPECT_LT(Length(parked.checks.at(0).must_go, parked.sample_step), 17.01);

  ChangingWorldOptions o;
  o.cut_depth = 1.5;
  const ChangingWorldScenario face = CoalFaceScenario(o);
  const ScenarioCheck& c = face.checks.at(0);
  // The old face (6 m at y = 18) must go, the new one (y = 19.5) appears.
  EXPECT_NEAR(LengthOn(c.must_go, Segment(7, 18, 13, 18), face.sample_step), 6.0, 0.3);
  EXPECT_NEAR(LengthOn(c.must_appear, Segment(13, 19.5, 7, 19.5), face.sample_step), 6.0, 0.11);
}

TEST(ChangingWorld, NamesAndValidation) {
  for (const std::string& name : ChangingWorldScenarioNames())
    EXPECT_EQ(ChangingWorldScenarioByName(name).name, name);
  EXPECT_THROW(ChangingWorldScenarioByName("nope"), std::invalid_argument);
  ChangingWorldOptions bad;
  bad.cut_depth = -1.0;
  EXPECT_NE(ValidateOptions(bad), "");
  EXPECT_THROW(CoalFaceScenario(bad), std::invalid_argument);
}

}  // namespace
}  // namespace minenav
