#include "pose_estimator/incremental_line_fitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace minenav {
namespace {

TEST(IncrementalLineFitter, SlidingWindowMatchesAFreshFit) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.05 * i;
    pts.emplace_back(20.0 + t * std::cos(0.7) + noise(rng), 30.0 + t * std::sin(0.7) + noise(rng));
  }
  IncrementalLineFitter sliding(pts[0]);
  const int w = 25;
  for (int i = 0; i < w; ++i) sliding.Add(pts[static_cast<size_t>(i)]);
  for (int start = 1; start + w <= 200; ++start) {
    sliding.Remove(pts[static_cast<size_t>(start - 1)]);
    sliding.Add(pts[static_cast<size_t>(start + w - 1)]);
    IncrementalLineFitter fresh;
    for (int i = start; i < start + w; ++i) fresh.Add(pts[static_cast<size_t>(i)]);
    const LineFit a = sliding.Fit(), b = fresh.Fit();
    ASSERT_TRUE(a.valid);
    EXPECT_NEAR((a.centroid - b.centroid).norm(), 0.0, 1e-9);
    EXPECT_NEAR(std::abs(a.direction.dot(b.direction)), 1.0, 1e-9);
    EXPECT_NEAR(a.rms, b.rms, 1e-7);
  }
  const LineFit f = sliding.Fit();
  EXPECT_NEAR(std::abs(f.direction.dot(Eigen::Vector2d(std::cos(0.7), std::sin(0.7)))), 1.0, 1e-3);
  EXPECT_NEAR(f.rms, 0.05, 0.02);
}

TEST(IncrementalLineFitter, ExactLineHasZeroResidualAndFewPointsAreInvalid) {
  IncrementalLineFitter f;
  f.Add({1, 1});
  EXPECT_FALSE(f.Fit().valid);
  f.Add({2, 3});
  f.Add({3, 5});
  const LineFit fit = f.Fit();
  ASSERT_TRUE(fit.valid);
  EXPECT_NEAR(fit.rms, 0.0, 1e-6);
  EXPECT_NEAR(std::abs(fit.direction.dot(Eigen::Vector2d(1, 2).normalized())), 1.0, 1e-12);
  f.Remove({1, 1});
  f.Remove({2, 3});
  f.Remove({3, 5});
  EXPECT_EQ(f.count(), 0);
  EXPECT_FALSE(f.Fit().valid);
}

}  // namespace
}  // namespace minenav
