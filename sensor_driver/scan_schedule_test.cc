#include "sensor_driver/scan_schedule.h"

#include <gtest/gtest.h>

namespace minenav {
namespace {

TruthReading Truth(int64_t utime, double x) {
  TruthReading t;
  t.utime = utime;
  t.pose = Pose2(x, 0.0, 0.0);
  return t;
}

// 20 Hz truth, 10 Hz scans starting at the first sample: a scan every other sample, at
// exactly the stamps t0 + k * 0.1 s, at the true pose of that time.
TEST(ScanScheduleTest, ScansAreStampedOnTheTruthClockAtTheInterpolatedPose) {
  ScanSchedule schedule;
  std::vector<DueScan> scans;
  const int64_t t0 = 1'000'000;
  for (int k = 0; k <= 20; ++k) {
    // x = t in seconds, but sampled 3 ms late so that scans fall between samples.
    const int64_t utime = t0 + k * 50'000 + (k > 0 ? 3'000 : 0);
    for (const DueScan& s : schedule.AddTruth(Truth(utime, 1e-6 * static_cast<double>(utime - t0)))) scans.push_back(s);
  }
  ASSERT_EQ(scans.size(), 11u);
  for (size_t i = 0; i < scans.size(); ++i) {
    EXPECT_EQ(scans[i].utime, t0 + static_cast<int64_t>(i) * 100'000);
    EXPECT_NEAR(scans[i].pose.x, 0.1 * static_cast<double>(i), 1e-12);  // linear truth: exact interpolation
  }
}

TEST(ScanScheduleTest, AGapSkipsTheScanTimesInsideIt) {
  ScanSchedule schedule;  // max gap 1 s
  int made = 0;
  for (int k = 0; k <= 10; ++k) made += static_cast<int>(schedule.AddTruth(Truth(k * 50'000, 0.0)).size());
  EXPECT_EQ(made, 6);  // 0 .. 0.5 s
  ScheduleNote note;
  const auto after_gap = schedule.AddTruth(Truth(3'500'000, 1.0), &note);
  EXPECT_EQ(note.skipped_scans, 29);
  EXPECT_EQ(note.gap_us, 3'000'000);
  ASSERT_EQ(after_gap.size(), 1u);
  EXPECT_EQ(after_gap[0].utime, 3'500'000);
  EXPECT_DOUBLE_EQ(after_gap[0].pose.x, 1.0);
}

TEST(ScanScheduleTest, TruthGoingBackRestartsTheScheduleAndRepeatsAreIgnored) {
  ScanSchedule schedule;
  schedule.AddTruth(Truth(5'000'000, 0.0));
  ScheduleNote note;
  EXPECT_TRUE(schedule.AddTruth(Truth(5'000'000, 0.0), &note).empty());
  EXPECT_TRUE(note.duplicate);
  const auto restarted = schedule.AddTruth(Truth(1'000'000, 2.0), &note);
  EXPECT_TRUE(note.restarted);
  EXPECT_EQ(note.went_back_us, 4'000'000);
  ASSERT_EQ(restarted.size(), 1u);
  EXPECT_EQ(restarted[0].utime, 1'000'000);
  EXPECT_EQ(*schedule.next_scan_utime(), 1'100'000);
}

}  // namespace
}  // namespace minenav
