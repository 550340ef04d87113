#include "viewer/log_replay.h"

#include <gtest/gtest.h>

#include "common/node/conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

template <typename T>
LogEvent Event(const std::string& channel, int64_t t, const T& m) {
  LogEvent e;
  e.channel = channel;
  e.timestamp = t;
  e.data = EncodeMessage(m);
  return e;
}

heartbeat_t Heartbeat(const std::string& process) {
  heartbeat_t h{};
  h.process = process;
  return h;
}

// scans at 0, 10, 20, 30; poses at 5, 15, 25; two processes' heartbeats at 1, 2, 21, 22.
std::vector<LogEvent> Events() {
  std::vector<LogEvent> e;
  for (int k = 0; k < 4; ++k) {
    ladar_scan_t s{};
    s.scan_id = k;
    e.push_back(Event("LADAR_SCAN", 10 * k, s));
    if (k < 3) e.push_back(Event("POSE", 10 * k + 5, pose_estimate_t{}));
    if (k == 0 || k == 2) {
      e.push_back(Event("HEARTBEAT", 10 * k + 1, Heartbeat("contour_mapper")));
      e.push_back(Event("HEARTBEAT", 10 * k + 2, Heartbeat("vehicle_sim")));
    }
  }
  std::sort(e.begin(), e.end(), [](const LogEvent& a, const LogEvent& b) { return a.timestamp < b.timestamp; });
  return e;
}

std::vector<std::string> Describe(const LogReplay& r, const std::vector<size_t>& idx) {
  std::vector<std::string> out;
  for (size_t i : idx) out.push_back(r.event(i).channel + "@" + std::to_string(r.event(i).timestamp));
  return out;
}

TEST(LogReplayTest, SeekGivesTheLatestOfEachChannelAndProcessAndEveryPose) {
  const LogReplay r(Events());
  EXPECT_EQ(r.start_utime(), 0);
  EXPECT_EQ(r.end_utime(), 30);
  EXPECT_EQ(Describe(r, r.Seek(24)),
            (std::vector<std::string>{"POSE@5", "POSE@15", "LADAR_SCAN@20", "HEARTBEAT@21", "HEARTBEAT@22"}));
  EXPECT_EQ(Describe(r, r.Seek(0)), (std::vector<std::string>{"LADAR_SCAN@0"}));
  EXPECT_TRUE(r.Seek(-1).empty());
}

TEST(LogReplayTest, BetweenIsHalfOpen) {
  const LogReplay r(Events());
  EXPECT_EQ(Describe(r, r.Between(5, 15)),
            (std::vector<std::string>{"LADAR_SCAN@10", "POSE@15"}));
  EXPECT_TRUE(r.Between(30, 100).empty());
}

TEST(LogReplayTest, StampsThatGoBackKeepFileOrder) {
  std::vector<LogEvent> e = Events();
  e.push_back(Event("POSE", 3, pose_estimate_t{}));  // after 30 in the file, stamped 3
  const LogReplay r(e);
  EXPECT_EQ(r.end_utime(), 30);
  EXPECT_EQ(Describe(r, r.Between(29, 30)), (std::vector<std::string>{"LADAR_SCAN@30", "POSE@30"}));
}

}  // namespace
}  // namespace minenav
