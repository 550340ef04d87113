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

}  // namespace
}  // namespace minenav
