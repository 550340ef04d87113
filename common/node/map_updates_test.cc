#include "common/node/map_updates.h"

#include <gtest/gtest.h>

#include "common/node/conversions.h"
#include "common/node/fake_bus.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"

namespace minenav {
namespace {

struct Received {
  std::vector<std::vector<Segment>> maps;
  std::vector<std::string> whats;
};

MapUpdates::Handler Record(Received* r) {
  return [r](const std::vector<Segment>& segments, const std::string& what) {
    r->maps.push_back(segments);
    r->whats.push_back(what);
  };
}

TEST(MapUpdatesTest, AMapIsHandedOnWhenItsSegmentsChangeNotWhenItIsRepublished) {
  FakeBus bus;
  Received got;
  MapUpdates updates(bus, "LINE_MAP", "", Record(&got));
  const std::vector<Segment> a = {{0, 0, 4, 0}, {4, 0, 4, 3}};
  const std::vector<Segment> b = {{0, 0, 4, 0}, {4, 0, 4, 3.5}};
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(a, 1, 1, "mine"));
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(a, 2, 2, "mine"));  // same walls, new version
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(b, 3, 1, "mine"));  // a restarted mapper: version 1 again
  bus.InjectMessage("CONTOUR_MAP", ContourMapToLcm(ContourMapMessage{}));  // not subscribed
  bus.HandleFor(0);
  ASSERT_EQ(got.maps.size(), 2u);
  EXPECT_TRUE(SameSegments(got.maps[0], a));
  EXPECT_TRUE(SameSegments(got.maps[1], b));
  EXPECT_EQ(got.whats[0], "LINE_MAP 'mine' version 1");
  EXPECT_EQ(got.whats[1], "LINE_MAP 'mine' version 1");
  EXPECT_EQ(updates.maps_handed_on(), 2);
}

TEST(MapUpdatesTest, AContourMapArrivesAsItsSegmentsWithClosedContoursClosed) {
  FakeBus bus;
  Received got;
  MapUpdates updates(bus, "LINE_MAP", "CONTOUR_MAP", Record(&got));
  ContourMapMessage map;
  map.version = 7;
  map.contours.push_back({1, true, {{0, 0}, {2, 0}, {2, 1}}});
  map.contours.push_back({2, false, {{5, 5}, {6, 5}}});
  bus.InjectMessage("CONTOUR_MAP", ContourMapToLcm(map));
  bus.InjectMessage("CONTOUR_MAP", ContourMapToLcm(map));
  bus.HandleFor(0);
  ASSERT_EQ(got.maps.size(), 1u);
  const std::vector<Segment> expected = {{0, 0, 2, 0}, {2, 0, 2, 1}, {2, 1, 0, 0}, {5, 5, 6, 5}};
  EXPECT_TRUE(SameSegments(got.maps[0], expected));
  EXPECT_EQ(got.whats[0], "CONTOUR_MAP version 7");
  // A closed contour of two points (the message check refuses it; the function alone does
  // not double its one segment).
  map.contours.push_back({3, true, {{9, 9}, {9.5, 9}}});
  std::vector<Segment> with_pair = expected;
  with_pair.emplace_back(9, 9, 9.5, 9);
  EXPECT_TRUE(SameSegments(ContourMapSegments(map), with_pair));
}

TEST(MapUpdatesTest, ABadMapReachesTheBusAsABadMessageAndTheLastGoodMapStands) {
  FakeBus bus;
  Received got;
  MapUpdates updates(bus, "LINE_MAP", "", [&](const std::vector<Segment>& segments, const std::string& what) {
    if (segments.size() > 2) throw std::runtime_error("too many");
    Record(&got)(segments, what);
  });
  const std::vector<Segment> a = {{0, 0, 4, 0}};
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(a, 1, 1, "mine"));
  bus.InjectMessage("LINE_MAP", SegmentsToLcm({{0, 0, 1, 0}, {1, 0, 2, 0}, {2, 0, 3, 0}}, 2, 2, "mine"));
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(a, 3, 3, "mine"));
  bus.HandleFor(0);
  ASSERT_EQ(got.maps.size(), 1u);  // the refused map was not taken as the last one
  EXPECT_EQ(updates.maps_handed_on(), 1);
}

// The rate bound: a changed map on every message (a map per scan, 10 a second) is handed on
// once per interval, the latest of those that waited; a republished map in use cancels one
// that waits.
TEST(MapUpdatesTest, WithARateBoundAChangedMapPerMessageIsHandedOnOncePerInterval) {
  FakeBus bus;
  ManualClock clock(1'000'000);
  Received got;
  MapUpdates updates(bus, "LINE_MAP", "", Record(&got));
  updates.SetRateBound(clock, 1'000'000);
  auto map = [](int i) { return std::vector<Segment>{{0, 0, 4, 0}, {4, 0, 4, 3.0 + 0.01 * i}}; };
  // 30 maps, each different, 0.1 s apart; HandOnDue before each (where a node takes a scan).
  for (int i = 0; i < 30; ++i) {
    updates.HandOnDue();
    bus.InjectMessage("LINE_MAP", SegmentsToLcm(map(i), i + 1, i + 1, "mine"));
    bus.HandleFor(0);
    clock.Advance(100'000);
  }
  // The first at once (t = 1.0 s), then the latest waiting at 2.0 s (map 9: maps 1..9 arrived
  // within the interval) and at 3.0 s (map 19); map 29 still waits.
  ASSERT_EQ(got.maps.size(), 3u);
  EXPECT_TRUE(SameSegments(got.maps[0], map(0)));
  EXPECT_TRUE(SameSegments(got.maps[1], map(9)));
  EXPECT_TRUE(SameSegments(got.maps[2], map(19)));
  EXPECT_TRUE(updates.map_waiting());
  clock.Advance(1'000'000);
  EXPECT_TRUE(updates.HandOnDue());
  ASSERT_EQ(got.maps.size(), 4u);
  EXPECT_TRUE(SameSegments(got.maps[3], map(29)));
  EXPECT_FALSE(updates.HandOnDue());  // nothing waits

  // A map waits; the map in use arrives again: nothing is handed on.
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(map(40), 40, 40, "mine"));
  bus.InjectMessage("LINE_MAP", SegmentsToLcm(map(29), 41, 41, "mine"));
  bus.HandleFor(0);
  EXPECT_FALSE(updates.map_waiting());
  clock.Advance(2'000'000);
  EXPECT_FALSE(updates.HandOnDue());
  EXPECT_EQ(updates.maps_handed_on(), 4);
}

TEST(MapUpdatesTest, AWaitingMapTheHandlerRefusesIsDroppedAndTheLastGoodMapStands) {
  FakeBus bus;
  ManualClock clock;
  Received got;
  MapUpdates updates(bus, "LINE_MAP", "", [&](const std::vector<Segment>& segments, const std::string& what) {
    if (segments.size() > 2) throw std::runtime_error("too many");
    Record(&got)(segments, what);
  });
  updates.SetRateBound(clock, 1'000'000);
  bus.InjectMessage("LINE_MAP", SegmentsToLcm({{0, 0, 4, 0}}, 1, 1, "mine"));
  bus.InjectMessage("LINE_MAP", SegmentsToLcm({{0, 0, 1, 0}, {1, 0, 2, 0}, {2, 0, 3, 0}}, 2, 2, "mine"));
  bus.HandleFor(0);
  EXPECT_TRUE(updates.map_waiting());
  clock.Advance(1'000'000);
  EXPECT_FALSE(updates.HandOnDue());  // refused (logged), not thrown
  EXPECT_FALSE(updates.map_waiting());
  ASSERT_EQ(got.maps.size(), 1u);
  EXPECT_EQ(updates.maps_handed_on(), 1);
}

}  // namespace
}  // namespace minenav
