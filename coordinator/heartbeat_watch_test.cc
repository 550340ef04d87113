#include "coordinator/heartbeat_watch.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace minenav {
namespace {

HeartbeatSample Beat(const std::string& process, HeartbeatState state, int64_t received,
                     const std::string& instance = "") {
  HeartbeatSample hb;
  hb.process = process;
  hb.instance = instance;
  hb.state = state;
  hb.received = received;
  hb.utime = received;
  hb.message = "msg";
  return hb;
}

TEST(HeartbeatWatchTest, ReadyMeansOkOrWarnAndRecent) {
  HeartbeatWatch w({"mapper", "tracker", "cutter"}, 3.0);
  EXPECT_EQ(w.NotReady(0), (std::vector<std::string>{"mapper: never seen", "tracker: never seen", "cutter: never seen"}));
  w.OnHeartbeat(Beat("mapper", HeartbeatState::kOk, 1'000'000));
  w.OnHeartbeat(Beat("tracker", HeartbeatState::kWarn, 1'000'000));
  w.OnHeartbeat(Beat("cutter", HeartbeatState::kStarting, 1'000'000));
  EXPECT_EQ(w.NotReady(1'500'000), std::vector<std::string>{"cutter: STARTING (msg)"});
  w.OnHeartbeat(Beat("cutter", HeartbeatState::kOk, 2'000'000));
  EXPECT_TRUE(w.AllReady(3'900'000));
  // 3 s after the mapper's and the tracker's last heartbeat: exactly the limit is still ready.
  EXPECT_TRUE(w.AllReady(4'000'000));
  EXPECT_EQ(w.NotReady(4'200'000),
            (std::vector<std::string>{"mapper: no heartbeat for 3.2 s", "tracker: no heartbeat for 3.2 s"}));
}

// A required process heard from a new pid was restarted (however short its silence); other
// processes' restarts and the same pid again are none; each restart is taken once.
TEST(HeartbeatWatchTest, ARequiredProcessFromANewPidWasRestarted) {
  HeartbeatWatch w({"tracker", "mapper/live"}, 3.0);
  auto beat = [&](const std::string& process, int pid, int64_t t, const std::string& instance = "") {
    HeartbeatSample hb = Beat(process, HeartbeatState::kOk, t, instance);
    hb.pid = pid;
    w.OnHeartbeat(hb);
  };
  beat("tracker", 640, 1'000'000);
  beat("mapper", 700, 1'000'000, "live");
  beat("viewer", 900, 1'000'000);
  beat("tracker", 640, 2'000'000);
  EXPECT_TRUE(w.TakeRestarts().empty()) << "the same pid again";
  beat("tracker", 812, 2'300'000);
  beat("viewer", 901, 2'300'000);
  beat("mapper", 701, 2'400'000, "live");
  EXPECT_EQ(w.TakeRestarts(),
            (std::vector<std::string>{"tracker (pid 812, was 640)", "mapper/live (pid 701, was 700)"}));
  EXPECT_TRUE(w.TakeRestarts().empty()) << "taken once";
  EXPECT_TRUE(w.AllReady(2'500'000)) << "restarted and heard: ready";
}

TEST(HeartbeatWatchTest, ErrorAndStoppingAreNotReadyAndInstancesAreTheirOwn) {
  HeartbeatWatch w({"ladar_driver/front", "planner"}, 3.0);
  w.OnHeartbeat(Beat("ladar_driver", HeartbeatState::kOk, 0, "rear"));
  w.OnHeartbeat(Beat("planner", HeartbeatState::kError, 0));
  EXPECT_EQ(w.NotReady(0), (std::vector<std::string>{"ladar_driver/front: never seen", "planner: ERROR (msg)"}));
  w.OnHeartbeat(Beat("ladar_driver", HeartbeatState::kOk, 0, "front"));
  w.OnHeartbeat(Beat("planner", HeartbeatState::kStopping, 0));
  EXPECT_EQ(w.NotReady(0), std::vector<std::string>{"planner: STOPPING (msg)"});
  EXPECT_TRUE(w.Ready("ladar_driver", 0)) << "the bare name is any instance";
}

}  // namespace
}  // namespace minenav
