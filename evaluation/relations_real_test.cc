// The Kuemmerle 2009 relation metric on the real Intel log of the datasets folder
// (dataset_readers/dataset_path.h); built only when the datasets are there (MINENAV_HAVE_DATASETS).
// The parsing and exact small cases are in relations_test.cc.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "dataset_readers/carmen_log.h"
#include "dataset_readers/dataset_path.h"
#include "evaluation/relations.h"

namespace minenav {
namespace {

using logger_test::Dataset;

std::vector<StampedPose> RobotPoses(const CarmenLog& log, int64_t shift_us) {
  std::vector<StampedPose> poses;
  for (const OdometryReading& o : log.scan_odometry) poses.push_back({o.utime + shift_us, o.pose});
  return poses;
}

std::vector<StampedPose> OdomPoses(const CarmenLog& log) {
  std::vector<StampedPose> poses;
  for (const OdometryReading& o : log.odometry) poses.push_back({o.utime, o.pose});
  return poses;
}

// Known answer (shared/datasets/SOURCES.md): GMapping's corrected Intel log, shifted to
// ipc time and scored with raw-log odometry correction, gives about 0.075 +- 0.086 m
// (Kuemmerle 2009's RBPF column: 0.070 +- 0.083).
TEST(RelationsRealTest, IntelGmappingKnownAnswer) {
  const std::vector<Relation> rel = LoadRelations(Dataset("intel.relations.txt"));
  ASSERT_EQ(rel.size(), 2984u);
  const CarmenLog corrected = ReadCarmenLog(Dataset("intel-corrected.log.gz"));
  const CarmenLog raw = ReadCarmenLog(Dataset("intel.clf.bz2"));
  const RelationScore s = ScoreRelations(rel, RobotPoses(corrected, 976052857337284), OdomPoses(raw));
  ASSERT_TRUE(s.ok) << s.reason;
  EXPECT_EQ(s.n, 2984);
  EXPECT_NEAR(s.translation.mean, 0.075, 0.005);
  EXPECT_NEAR(s.translation.std, 0.086, 0.005);
  std::printf("intel GMapping: N %lld, corrected %lld, trans %.4f +- %.4f m, rot %.3f +- %.3f deg\n",
              static_cast<long long>(s.n), static_cast<long long>(s.odometry_corrected), s.translation.mean,
              s.translation.std, s.rotation.mean, s.rotation.std);

  // Raw odometry scores far worse: the gap between the two is what a SLAM system is for.
  const RelationScore odo = ScoreRelations(rel, RobotPoses(raw, 0), {});
  ASSERT_TRUE(odo.ok) << odo.reason;
  EXPECT_EQ(odo.n, 2984);
  EXPECT_EQ(odo.odometry_corrected, 0);  // every relation time is a FLASER time
  EXPECT_GT(odo.translation.mean, 2.0 * s.translation.mean);
  std::printf("intel odometry: trans %.4f +- %.4f m, rot %.3f +- %.3f deg\n", odo.translation.mean,
              odo.translation.std, odo.rotation.mean, odo.rotation.std);
}

}  // namespace
}  // namespace minenav
