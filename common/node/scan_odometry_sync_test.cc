#include "common/node/scan_odometry_sync.h"

#include <gtest/gtest.h>

namespace minenav {
namespace {

OdometryReading Odo(int64_t utime, double x) {
  OdometryReading r;
  r.utime = utime;
  r.pose = Pose2(x, 0.0, 0.0);
  return r;
}

LadarScan Scan(int64_t utime) {
  LadarScan s;
  s.utime = utime;
  s.scan_id = utime;
  return s;
}

TEST(ScanOdometrySyncTest, ScansWaitForLaterOdometryAndAreInterpolated) {
  ScanOdometrySync sync;
  EXPECT_TRUE(sync.AddOdometry(Odo(1'000'000, 1.0)));
  sync.AddScan(Scan(1'500'000));
  EXPECT_TRUE(sync.TakeReady().empty());  // no reading at or after 1.5 s yet
  EXPECT_EQ(sync.pending(), 1u);
  sync.AddOdometry(Odo(2'000'000, 3.0));
  const auto ready = sync.TakeReady();
  ASSERT_EQ(ready.size(), 1u);
  ASSERT_TRUE(ready[0].odometry);
  EXPECT_DOUBLE_EQ(ready[0].odometry->x, 2.0);  // halfway between 1 and 3
  EXPECT_FALSE(ready[0].exact);
  EXPECT_EQ(ready[0].scan.utime, 1'500'000);
  // An exactly stamped reading.
  sync.AddScan(Scan(2'000'000));
  const auto exact = sync.TakeReady();
  ASSERT_EQ(exact.size(), 1u);
  EXPECT_TRUE(exact[0].exact);
  EXPECT_DOUBLE_EQ(exact[0].odometry->x, 3.0);
}

TEST(ScanOdometrySyncTest, ScansComeOutInArrivalOrderAndAtShutdownWithTheNewestReading) {
  ScanOdometrySync sync;
  sync.AddOdometry(Odo(0, 0.0));
  sync.AddScan(Scan(100'000));
  sync.AddScan(Scan(200'000));
  sync.AddScan(Scan(5'000'000));  // far beyond any reading
  EXPECT_TRUE(sync.TakeReady().empty());
  const auto ready = sync.TakeReady(/*at_shutdown=*/true);
  ASSERT_EQ(ready.size(), 3u);
  EXPECT_EQ(ready[0].scan.utime, 100'000);
  EXPECT_EQ(ready[1].scan.utime, 200'000);
  ASSERT_TRUE(ready[0].odometry);  // within the 1 s gap of the newest reading
  EXPECT_FALSE(ready[2].odometry);  // 5 s from it: no odometry
  EXPECT_EQ(sync.pending(), 0u);
}

TEST(ScanOdometrySyncTest, TimeGoingBackClearsTheHistory) {
  ScanOdometrySync sync;
  sync.AddOdometry(Odo(10'000'000, 5.0));
  sync.AddOdometry(Odo(11'000'000, 6.0));
  EXPECT_FALSE(sync.AddOdometry(Odo(1'000'000, 0.0)));
  ASSERT_EQ(sync.odometry().size(), 1u);
  EXPECT_EQ(sync.odometry().front().utime, 1'000'000);
}

TEST(ScanOdometrySyncTest, HistoryKeepsTheLastSixtySeconds) {
  ScanOdometrySync sync;
  for (int k = 0; k <= 100; ++k) sync.AddOdometry(Odo(int64_t{k} * 1'000'000, k));
  EXPECT_EQ(sync.odometry().front().utime, 40'000'000);
  EXPECT_EQ(sync.odometry().back().utime, 100'000'000);
}

TEST(ScanOdometrySyncTest, TooManyWaitingScansDropTheOldest) {
  ScanOdometrySyncOptions o;
  o.max_pending = 3;
  ScanOdometrySync sync(o);
  for (int k = 1; k <= 3; ++k) EXPECT_TRUE(sync.AddScan(Scan(k)));
  EXPECT_FALSE(sync.AddScan(Scan(4)));
  EXPECT_EQ(sync.dropped(), 1);
  sync.AddOdometry(Odo(10, 0.0));
  const auto ready = sync.TakeReady();
  ASSERT_EQ(ready.size(), 3u);
  EXPECT_EQ(ready.front().scan.utime, 2);
}

// Issue 11, item 5: odometry stamped INT64_MAX at 20 Hz between real readings cleared the
// history every time and most real scans were skipped as "no odometry".
TEST(ScanOdometrySyncTest, LoneFarOffReadingsNeitherResetNorBlockTheHistory) {
  ScanOdometrySync sync;
  int with_odometry = 0, scans = 0;
  for (int k = 0; k < 200; ++k) {
    const int64_t t = 1'700'000'000'000'000 + int64_t{k} * 50'000;  // wall-clock time, 2023
    EXPECT_TRUE(sync.AddOdometry(Odo(t, 0.05 * k)));
    OdometryReading hostile = Odo(k % 2 == 0 ? INT64_MAX : 0, 99.0);
    EXPECT_TRUE(sync.AddOdometry(hostile)) << "a lone far-off reading must not clear the history";
    if (k % 5 == 0) {
      sync.AddScan(Scan(t - 25'000));
      for (const SyncedScan& s : sync.TakeReady()) {
        ++scans;
        with_odometry += s.odometry.has_value();
        if (s.odometry) {
          EXPECT_LT(s.odometry->x, 10.0);  // never the hostile pose
        }
      }
    }
  }
  EXPECT_EQ(scans, 40);
  EXPECT_EQ(with_odometry, 40);
  EXPECT_GE(sync.rejected_odometry(), 199);
  EXPECT_GT(sync.odometry().size(), 100u);
}

TEST(ScanOdometrySyncTest, AFarJumpFollowedByOrderedReadingsIsARestart) {
  ScanOdometrySync sync;
  for (int k = 0; k < 10; ++k) sync.AddOdometry(Odo(500'000'000 + k * 50'000, 1.0));
  // A log replayed from its start: far back, then in order.
  EXPECT_TRUE(sync.AddOdometry(Odo(1'000'000, 0.0)));
  EXPECT_TRUE(sync.AddOdometry(Odo(1'050'000, 0.1)));
  EXPECT_FALSE(sync.AddOdometry(Odo(1'100'000, 0.2)));  // confirmed: history restarted
  ASSERT_EQ(sync.odometry().size(), 3u);
  EXPECT_EQ(sync.odometry().front().utime, 1'000'000);
  EXPECT_EQ(sync.rejected_odometry(), 0);
}

// Issue 11, item 5: a scan stamped INT64_MAX held up every scan behind it for ~9 s.
TEST(ScanOdometrySyncTest, AScanStampedFarAheadDoesNotBlockTheOthers) {
  ScanOdometrySync sync;
  sync.AddOdometry(Odo(1'000'000, 0.0));
  sync.AddScan(Scan(INT64_MAX));
  sync.AddScan(Scan(1'020'000));
  sync.AddOdometry(Odo(1'050'000, 1.0));
  const auto ready = sync.TakeReady();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_FALSE(ready[0].odometry);  // released without odometry: the caller skips it
  ASSERT_TRUE(ready[1].odometry);
  EXPECT_NEAR(ready[1].odometry->x, 0.4, 1e-9);
}

TEST(ScanOdometrySyncTest, AScanStampedInt64MinGetsNoOdometry) {
  ScanOdometrySync sync;
  sync.AddOdometry(Odo(1'000'000, 0.0));
  sync.AddOdometry(Odo(1'050'000, 1.0));
  sync.AddScan(Scan(INT64_MIN));
  const auto ready = sync.TakeReady();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_FALSE(ready[0].odometry) << "the gap limit must hold for any stamp";
}

}  // namespace
}  // namespace minenav
