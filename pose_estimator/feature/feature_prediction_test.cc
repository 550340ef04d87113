#include "pose_estimator/feature/feature_prediction.h"

#include <gtest/gtest.h>

#include <random>

#include "pose_estimator/feature/feature_test_util.h"

namespace minenav {
namespace {

using testing::AddBox;
using testing::RoomWithPillar;

int Count(const PredictedFeatures& p, FeatureType t, bool occlusion = false) {
  int n = 0;
  for (const Feature& f : p.features) n += f.type == t && (t == FeatureType::kLine || f.occlusion == occlusion);
  return n;
}

TEST(FeaturePrediction, SquareRoomFromInsideSeesFourCornersAndFourWallsInOrder) {
  std::vector<Segment> room;
  AddBox(&room, 0, 0, 10, 6);
  const FeatureMap map = BuildFeatureMap(room).map;
  ASSERT_EQ(map.vertices.size(), 4u);
  const Eigen::Vector2d p(4, 2);
  const PredictedFeatures pred = PredictFeatures(map, p);
  EXPECT_EQ(Count(pred, FeatureType::kCorner), 4);
  EXPECT_EQ(Count(pred, FeatureType::kCorner, true), 0);
  EXPECT_EQ(Count(pred, FeatureType::kLine), 4);
  double last = -kPi - 1e-9;
  for (const Feature& f : pred.features) {
    const Eigen::Vector2d q = f.type == FeatureType::kCorner ? f.position : 0.5 * (f.start + f.end);
    const double a = std::atan2(q.y() - p.y(), q.x() - p.x());
    EXPECT_GE(a, last);
    last = a;
    if (f.type == FeatureType::kCorner) {
      EXPECT_NEAR(f.concave_angle, kPi / 2, 1e-9);
      // Room corners seen from inside: the bisector points back into the room.
      EXPECT_LT((f.position + 0.1 * Eigen::Vector2d(std::cos(f.bisector), std::sin(f.bisector)) -
                 Eigen::Vector2d(5, 3)).norm(),
                (f.position - Eigen::Vector2d(5, 3)).norm());
    } else {
      EXPECT_TRUE(f.length == 10.0 || f.length == 6.0) << f.length;
    }
  }
  for (const VertexLabel& l : pred.vertex_labels) {
    EXPECT_TRUE(l.visible);
    EXPECT_FALSE(l.occluding);
  }
}

TEST(FeaturePrediction, PillarHidesItsFarCornerAndPartOfTheWallBehind) {
  const FeatureMap map = BuildFeatureMap(RoomWithPillar()).map;
  // From (3, 3.5) the pillar (7..8, 3..4) shows its west face only.
  const PredictedFeatures pred = PredictFeatures(map, Eigen::Vector2d(3, 3.5));
  auto label = [&](double x, double y) {
    for (size_t v = 0; v < map.vertices.size(); ++v) {
      if ((map.vertices[v] - Eigen::Vector2d(x, y)).norm() < 1e-9) return pred.vertex_labels[v];
    }
    ADD_FAILURE() << "no vertex at " << x << ", " << y;
    return VertexLabel{};
  };
  EXPECT_TRUE(label(7, 3).visible);
  EXPECT_TRUE(label(7, 3).occluding);
  EXPECT_TRUE(label(7, 4).visible);
  EXPECT_TRUE(label(7, 4).occluding);
  EXPECT_FALSE(label(8, 3).visible);
  EXPECT_FALSE(label(8, 4).visible);
  EXPECT_TRUE(label(0, 0).visible);
  EXPECT_FALSE(label(0, 0).occluding);
  // The east wall x = 12 is cut in two by the pillar's shadow.
  int east_pieces = 0;
  for (const Feature& f : pred.features) {
    if (f.type == FeatureType::kLine && std::abs(f.start.x() - 12) < 1e-9 && std::abs(f.end.x() - 12) < 1e-9) {
      ++east_pieces;
    }
  }
  EXPECT_EQ(east_pieces, 2);
  EXPECT_EQ(Count(pred, FeatureType::kCorner, true), 2);
}

// Brute-force reference: a vertex is visible if the ray to it meets nothing nearer; it is
// occluding if just past it on one side the ray runs on to something clearly farther.
TEST(FeaturePrediction, VertexLabelsAgreeWithBruteForceRayCasting) {
  std::vector<Segment> world = RoomWithPillar();
  AddBox(&world, 2, 5.5, 2.6, 6.1);
  AddBox(&world, 9, 1, 9.4, 2.2);
  const FeatureMap map = BuildFeatureMap(world).map;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> ux(0.3, 11.7), uy(0.3, 7.7);
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::Vector2d p(ux(rng), uy(rng));
    bool inside_obstacle = (p.x() > 6.9 && p.x() < 8.1 && p.y() > 2.9 && p.y() < 4.1) ||
                           (p.x() > 1.9 && p.x() < 2.7 && p.y() > 5.4 && p.y() < 6.2) ||
                           (p.x() > 8.9 && p.x() < 9.5 && p.y() > 0.9 && p.y() < 2.3) ||
                           (p.x() > 10 && p.y() > 5);
    if (inside_obstacle) continue;
    const PredictedFeatures pred = PredictFeatures(map, p);
    for (size_t v = 0; v < map.vertices.size(); ++v) {
      const Eigen::Vector2d q = map.vertices[v];
      const double range = (q - p).norm();
      const double bearing = std::atan2(q.y() - p.y(), q.x() - p.x());
      // Skip vertices seen exactly edge-on, where visibility is a matter of definition.
      bool edge_on = false;
      for (int s : map.vertex_segments[v]) {
        const Segment& seg = map.segments[static_cast<size_t>(s)];
        edge_on = edge_on || std::abs(SignedDistanceToLine(p, seg)) < 1e-3;
      }
      if (edge_on) continue;
      const auto hit = CastRay(p, bearing, world, 100.0);
      // A ray aimed exactly at a shared vertex may slip through the crack: nothing nearer.
      const bool visible = !hit || hit->range > range - 1e-4;
      EXPECT_EQ(pred.vertex_labels[v].visible, visible) << "vertex " << q.transpose() << " from " << p.transpose();
      if (visible) {
        const double eps = 1e-4;
        const auto left = CastRay(p, bearing + eps, world, 100.0);
        const auto right = CastRay(p, bearing - eps, world, 100.0);
        // Farther, and not on a segment of this vertex (a face seen at a grazing angle).
        const auto& own = map.vertex_segments[v];
        auto far = [&](const std::optional<RayHit>& h) {
          if (!h) return true;
          const Segment& hs = world[static_cast<size_t>(h->segment)];
          bool on_own = false;
          for (int s : own) {
            const Segment& os = map.segments[static_cast<size_t>(s)];
            on_own = on_own || ((os.a - hs.a).norm() < 1e-9 && (os.b - hs.b).norm() < 1e-9);
          }
          return !on_own && h->range > range + 0.01;
        };
        EXPECT_EQ(pred.vertex_labels[v].occluding, far(left) || far(right))
            << "vertex " << q.transpose() << " from " << p.transpose();
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(FeaturePrediction, MaximumRangeLimitsTheSegmentsConsidered) {
  std::vector<Segment> world;
  AddBox(&world, 0, 0, 100, 6);  // a long corridor
  const FeatureMap map = BuildFeatureMap(world).map;
  PredictionOptions o;
  o.max_range = 20.0;
  const PredictedFeatures pred = PredictFeatures(map, Eigen::Vector2d(5, 3), o);
  for (const Feature& f : pred.features) {
    if (f.type == FeatureType::kCorner) {
      EXPECT_LT(f.position.x(), 21.0);
    } else {
      EXPECT_LE(std::min(f.start.x(), f.end.x()), 21.0);
    }
  }
  EXPECT_EQ(pred.segments_in_range, 3);  // the far end wall is out of range
}

TEST(FeaturePrediction, CollinearSegmentsMergeIntoOneLineWithoutCorner) {
  std::vector<Segment> world = {{0, 0, 5, 0}, {5, 0, 10, 0.0001}, {10, 0.0001, 10, 6},
                                {10, 6, 0, 6}, {0, 6, 0, 0}};
  const PredictedFeatures pred = PredictFeatures(BuildFeatureMap(world).map, Eigen::Vector2d(5, 3));
  EXPECT_EQ(Count(pred, FeatureType::kCorner), 4);
  EXPECT_EQ(Count(pred, FeatureType::kLine), 4);
}

TEST(FeaturePrediction, EmptyMapPredictsNothing) {
  const PredictedFeatures pred = PredictFeatures(BuildFeatureMap({}).map, Eigen::Vector2d(0, 0));
  EXPECT_TRUE(pred.features.empty());
}

}  // namespace
}  // namespace minenav
