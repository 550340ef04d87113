#include "pose_estimator/feature/feature_matching.h"

#include <gtest/gtest.h>

#include "pose_estimator/feature/feature_extraction.h"
#include "pose_estimator/feature/feature_prediction.h"
#include "pose_estimator/feature/feature_test_util.h"

namespace minenav {
namespace {

using testing::AddBox;
using testing::RoomWithPillar;
using testing::SimulateScan;

struct Scene {
  std::vector<Feature> sensed, model, model_world;
};

// Sensed features of an exact or noisy scan from `truth`; model features predicted from
// `guess` and moved into the sensor frame with it.
Scene MakeScene(const std::vector<Segment>& map_segments, const std::vector<Segment>& world,
                const Pose2& truth, const Pose2& guess, double sigma = 0.0) {
  Scene s;
  ExtractionOptions extraction;
  if (sigma > 0.0) extraction.noise_sigma = sigma;  // the extractor knows its sensor
  s.sensed = ExtractFeatures(SimulateScan(world, truth, 1000, sigma), extraction).features;
  const PredictedFeatures pred = PredictFeatures(BuildFeatureMap(map_segments).map, guess.translation());
  for (const Feature& f : pred.features) {
    s.model_world.push_back(f);
    s.model.push_back(TransformFeature(f, guess));
  }
  std::vector<size_t> order(s.model.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return s.model[a].Azimuth() < s.model[b].Azimuth(); });
  std::vector<Feature> m, w;
  for (size_t i : order) {
    m.push_back(s.model[i]);
    w.push_back(s.model_world[i]);
  }
  s.model = m;
  s.model_world = w;
  return s;
}

// A match is right if the sensed feature, moved into the map with the true pose, lies on
// its model feature.
int CountWrong(const Scene& s, const FeatureMatchResult& r, const Pose2& truth) {
  int wrong = 0;
  for (const FeaturePair& p : r.pairs) {
    const Feature sw = TransformFeature(s.sensed[static_cast<size_t>(p.sensed)], truth.inverse());
    const Feature& m = s.model_world[static_cast<size_t>(p.model)];
    if (m.type == FeatureType::kCorner) {
      wrong += (sw.position - m.position).norm() > 0.2;
    } else {
      wrong += std::abs(m.SignedDistance(0.5 * (sw.start + sw.end))) > 0.2 ||
               std::abs(std::sin(sw.orientation - m.orientation)) > 0.05;
    }
  }
  return wrong;
}

TEST(FeatureMatching, UnaryBoundsAndProperties) {
  MatchingOptions o;
  const Feature c = MakeCorner({5, 0}, {-1, 1}, {-1, -1}, false);
  Feature moved = c;
  moved.position = {5.5, 0.2};
  EXPECT_TRUE(UnaryConsistent(c, moved, o));
  moved.position = {6.5, 0};  // range differs by more than poserr
  EXPECT_FALSE(UnaryConsistent(c, moved, o));
  Feature sharp = MakeCorner({5, 0}, {-1, 0.5}, {-1, -0.5}, false);  // 53 deg, not 90
  EXPECT_FALSE(UnaryConsistent(c, sharp, o));
  Feature turned = MakeCorner({5, 0}, {-1, 0.2}, {0.2, -1}, false);  // bisector off by 39 deg
  EXPECT_FALSE(UnaryConsistent(c, turned, o));
  const Feature l = MakeLine({3, -2}, {3, 2});
  EXPECT_TRUE(UnaryConsistent(l, MakeLine({3.8, -2}, {3.8, 2}), o));
  EXPECT_FALSE(UnaryConsistent(l, MakeLine({4.7, -2}, {4.7, 2}), o));     // beyond poserr + disterr
  EXPECT_FALSE(UnaryConsistent(l, MakeLine({-3, 2}, {-3, -2}), o));      // behind the sensor
  EXPECT_FALSE(UnaryConsistent(l, c, o));                                // types differ
}

TEST(FeatureMatching, BinaryConstraintsArePoseInvariant) {
  MatchingOptions o;
  const Feature c1 = MakeCorner({5, 1}, {-1, 0}, {0, -1}, false);
  const Feature c2 = MakeCorner({5, -3}, {-1, 0}, {0, 1}, false);
  const Feature l1 = MakeLine({5, -3}, {5, 1});
  const Feature l2 = MakeLine({0, -3}, {5, -3});
  const Pose2 move(0.7, -0.4, 0.5);
  auto t = [&](const Feature& f) { return TransformFeature(f, move); };
  EXPECT_TRUE(BinaryConsistent(c1, t(c1), c2, t(c2), o));
  EXPECT_TRUE(BinaryConsistent(l1, t(l1), l2, t(l2), o));
  EXPECT_TRUE(BinaryConsistent(c1, t(c1), l2, t(l2), o));
  EXPECT_TRUE(BinaryConsistent(l1, t(l1), c2, t(c2), o));
  Feature far = c2;
  far.position.y() -= 1.0;
  EXPECT_FALSE(BinaryConsistent(c1, t(c1), far, t(c2), o));
  EXPECT_FALSE(BinaryConsistent(l1, t(l1), l1, t(l2), o));  // 0 vs 90 deg apart
  const Feature c3 = MakeCorner({0, -3}, {1, 0}, {0, 1}, false);
  EXPECT_FALSE(BinaryConsistent(l1, t(l1), c1, t(c3), o));  // corner on the line vs 5 m off
}

TEST(FeatureMatching, MatchesEverySensedFeatureOfACleanScanCorrectly) {
  const auto world = RoomWithPillar();
  const Pose2 truth(3, 3.5, 0.2);
  const Pose2 guess(3.4, 3.2, 0.25);
  const Scene s = MakeScene(world, world, truth, guess);
  const FeatureMatchResult r = MatchFeatures(s.sensed, s.model);
  EXPECT_TRUE(r.search_complete);
  EXPECT_EQ(CountWrong(s, r, truth), 0);
  EXPECT_GE(r.pairs.size(), s.sensed.size() - 1);
  EXPECT_GE(r.pairs.size(), 10u);
}

TEST(FeatureMatching, LargeHeadingErrorNeedsOnlyAWideAngerr) {
  const auto world = RoomWithPillar();
  const Pose2 truth(4, 5.5, -0.3);
  const Pose2 guess(4.6, 5.0, -0.3 + DegToRad(40));
  const Scene s = MakeScene(world, world, truth, guess, 0.05);
  MatchingOptions o;
  EXPECT_LT(MatchFeatures(s.sensed, s.model, o).pairs.size(), 3u);  // angerr 5 deg: lost
  o.angerr = DegToRad(45);
  const FeatureMatchResult r = MatchFeatures(s.sensed, s.model, o);
  EXPECT_EQ(CountWrong(s, r, truth), 0);
  EXPECT_GE(r.pairs.size(), 8u);
}

TEST(FeatureMatching, ClutterNotInTheMapStaysUnmatched) {
  const auto map = RoomWithPillar();
  auto world = map;
  AddBox(&world, 2, 1, 3, 1.8);  // a machine parked in the room
  const Pose2 truth(5, 5, 1.0);
  const Scene s = MakeScene(map, world, truth, Pose2(5.3, 4.6, 1.05), 0.05);
  const FeatureMatchResult r = MatchFeatures(s.sensed, s.model);
  EXPECT_EQ(CountWrong(s, r, truth), 0);
  EXPECT_GE(r.pairs.size(), 8u);
}

TEST(FeatureMatching, NothingToMatch) {
  EXPECT_TRUE(MatchFeatures({}, {}).pairs.empty());
  const Feature c = MakeCorner({5, 1}, {-1, 0}, {0, -1}, false);
  EXPECT_TRUE(MatchFeatures({c}, {}).pairs.empty());
}

}  // namespace
}  // namespace minenav
