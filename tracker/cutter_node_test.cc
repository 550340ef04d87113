// cutter's node through the fake bus: a cut task without a face in reach fails on
// TASK_STATUS with its reason and never moves the vehicle; an accepted task drives and
// commands the appendages; a malformed task is counted bad; the heartbeat says why it
// stopped; CUTTER_STATE staleness is judged on the node's clock.

#include "tracker/cutter_node.h"

#include <gtest/gtest.h>

#include "common/config_testing.h"
#include "common/node/conversions.h"
#include "common/node/fake_runtime.h"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_status_t.hpp"
#include "tracker/cutter_conversions.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

struct Harness {
  explicit Harness(const CutterNodeOptions& o = {}) : node(fake.runtime(), o) {}
  void Tick(int64_t dt_us = 100'000) {
    clock.Advance(dt_us);
    runtime->SpinOnce(0);
  }
  void Pose(const Pose2& p) {
    PoseEstimate e;
    e.utime = clock.NowUtime();
    e.pose = p;
    e.converged = true;
    e.status = "ok";
    bus->InjectMessage("POSE", ToLcm(e));
  }
  void State(double boom, bool drum) {
    CutterState s;
    s.utime = 0;  // the vehicle's clock: ignored
    s.boom_height = boom;
    s.drum_on = drum;
    bus->InjectMessage("CUTTER_STATE", ToLcm(s));
  }
  void Task(int64_t seq, double depth, std::optional<Segment> face, int8_t action = cutter_command_t::SUMP) {
    CutterCommand c;
    c.seq = seq;
    c.sump_depth = depth;
    c.face = face;
    cutter_command_t m = ToLcm(c);
    m.action = action;
    bus->InjectMessage("CUT_TASK", m);
  }
  // The vehicle at `at` with its boom up, then the task `seq` (a 1 m cut into `face`).
  void Submit(int64_t seq, const Pose2& at, const Segment& face) {
    Pose(at);
    State(2.4, false);
    Tick();
    Task(seq, 1.0, face);
    Tick();
  }
  ManualClock clock{kT0};
  FakeRuntime fake{clock, 1.0, "cutter"};
  FakeBus* bus = &fake.bus();
  NodeRuntime* runtime = &fake.runtime();
  CutterNode node;
};

TEST(CutterNodeTest, ACutWithoutAFaceInReachFailsWithItsReasonAndNothingMoves) {
  Harness h;
  h.Submit(7, Pose2(0, 0, 0), Segment(16, -3, 16, 3));
  h.Tick();
  const auto status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  ASSERT_EQ(status.size(), 1u);
  EXPECT_EQ(status[0].task_id, 7);
  EXPECT_EQ(status[0].state, task_status_t::FAILED);
  EXPECT_EQ(status[0].message, "refused: no face in reach: the face is 11.00 m ahead of the cutterhead (reach 3.00 m)");
  EXPECT_TRUE(h.bus->PublishedOn("DRIVE_COMMAND").empty());
  EXPECT_TRUE(h.bus->PublishedOn("CUTTER_COMMAND").empty());
  h.Tick(1'000'000);
  const auto hb = h.bus->Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_FALSE(hb.empty());
  EXPECT_EQ(hb.back().state, heartbeat_t::WARN);
  EXPECT_EQ(hb.back().message, status[0].message);
}

TEST(CutterNodeTest, AnAcceptedCutRaisesTheBoomThenSquaresUp) {
  Harness h;
  h.Pose(Pose2(10, 0, 0.05));
  h.State(1.0, false);
  h.Tick();
  h.Task(8, 1.0, std::nullopt);  // no face given and no map yet: refused
  h.Tick();
  EXPECT_EQ(h.bus->Decoded<task_status_t>("TASK_STATUS").back().message,
            "refused: no face in reach: nothing in the map within 3.0 m ahead of the cutterhead");
  h.Task(9, 1.0, Segment(16, -3, 16, 3));
  h.Tick();
  auto status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  EXPECT_EQ(status.back().task_id, 9);
  EXPECT_EQ(status.back().state, task_status_t::ACTIVE);
  h.Tick();  // the first control tick of the cut
  const auto commands = h.bus->Decoded<cutter_command_t>("CUTTER_COMMAND");
  ASSERT_EQ(commands.size(), 1u);
  EXPECT_EQ(commands[0].action, cutter_command_t::SET_BOOM);
  EXPECT_DOUBLE_EQ(commands[0].boom_height, 2.4);
  h.State(2.4, false);
  h.Pose(Pose2(10, 0, 0.05));
  h.Tick();  // the state arrives (after this tick's control step)
  h.Tick();  // the boom is up: squaring up
  h.Tick();
  const auto drives = h.bus->Decoded<drive_command_t>("DRIVE_COMMAND");
  ASSERT_GE(drives.size(), 2u);
  EXPECT_EQ(drives.back().mode, drive_command_t::TURN_IN_PLACE);
  // A STOP on the task channel with the cut's seq cancels: one last STOP, the drum told to
  // stop, CANCELED.
  h.Task(9, 0.0, std::nullopt, cutter_command_t::STOP);
  h.Tick();  // the cancel arrives
  h.Tick();  // the last word
  EXPECT_EQ(h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").back().mode, drive_command_t::STOP);
  EXPECT_EQ(h.bus->Decoded<cutter_command_t>("CUTTER_COMMAND").back().action, cutter_command_t::STOP);
  status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  EXPECT_EQ(status.back().state, task_status_t::CANCELED);
  EXPECT_EQ(status.back().message, "canceled by the sender");
  const size_t n = h.bus->PublishedOn("DRIVE_COMMAND").size();
  h.Tick();
  h.Tick();
  EXPECT_EQ(h.bus->PublishedOn("DRIVE_COMMAND").size(), n);  // silent when no cut is active
  // Every DRIVE_COMMAND numbered 0, 1, 2, ... (a log of the mission counted the cutter's 934
  // commands as all seq 0 before).
  const auto all = h.bus->Decoded<drive_command_t>("DRIVE_COMMAND");
  ASSERT_EQ(all.size(), n);
  for (size_t k = 0; k < all.size(); ++k) EXPECT_EQ(all[k].seq, static_cast<int64_t>(k));
}

// The coordinator re-sends each task until it is acknowledged: a repeat of the cut under way
// re-publishes its status and does not restart it; a STOP of another task is not this cut's;
// the repeats of a canceled (or refused) cut re-publish how it ended and start nothing.
TEST(CutterNodeTest, RepeatedTasksAreAcknowledgedNotRestarted) {
  Harness h;
  h.Submit(21, Pose2(10, 0, 0.05), Segment(16, -3, 16, 3));
  h.State(2.4, false);
  h.Pose(Pose2(10, 0, 0.05));
  for (int k = 0; k < 4; ++k) h.Tick();
  ASSERT_EQ(h.node.cutter().status().step, "squaring up");
  const size_t boom_commands = h.bus->PublishedOn("CUTTER_COMMAND").size();
  const size_t statuses = h.bus->PublishedOn("TASK_STATUS").size();
  h.Task(21, 1.0, Segment(16, -3, 16, 3));  // the repeat
  h.Tick();
  auto status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  ASSERT_EQ(status.size(), statuses + 1);
  EXPECT_EQ(status.back().task_id, 21);
  EXPECT_EQ(status.back().state, task_status_t::ACTIVE);
  EXPECT_EQ(h.node.cutter().status().step, "squaring up") << "not restarted (it would raise the boom first)";
  EXPECT_EQ(h.bus->PublishedOn("CUTTER_COMMAND").size(), boom_commands);
  EXPECT_EQ(h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").back().mode, drive_command_t::TURN_IN_PLACE);
  // A STOP of another task: not this cut's.
  h.Task(20, 0.0, std::nullopt, cutter_command_t::STOP);
  h.Tick();
  EXPECT_TRUE(h.node.cutter().active());
  EXPECT_EQ(h.bus->Decoded<drive_command_t>("DRIVE_COMMAND").back().mode, drive_command_t::TURN_IN_PLACE);
  // Its own STOP cancels; the STOP and the task repeated re-publish CANCELED, nothing moves.
  h.Task(21, 0.0, std::nullopt, cutter_command_t::STOP);
  h.Tick();
  h.Tick();
  EXPECT_EQ(h.bus->Decoded<task_status_t>("TASK_STATUS").back().state, task_status_t::CANCELED);
  const size_t drives = h.bus->PublishedOn("DRIVE_COMMAND").size();
  const size_t before = h.bus->PublishedOn("TASK_STATUS").size();
  h.Task(21, 0.0, std::nullopt, cutter_command_t::STOP);
  h.Tick();
  h.Task(21, 1.0, Segment(16, -3, 16, 3));
  h.Tick();
  h.Tick();
  status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  ASSERT_EQ(status.size(), before + 2);
  for (size_t k = before; k < status.size(); ++k) {
    EXPECT_EQ(status[k].task_id, 21);
    EXPECT_EQ(status[k].state, task_status_t::CANCELED);
    EXPECT_EQ(status[k].message, "canceled by the sender");
  }
  EXPECT_FALSE(h.node.cutter().active());
  EXPECT_EQ(h.bus->PublishedOn("DRIVE_COMMAND").size(), drives) << "nothing moves";
  // A refused task repeated: the refusal again, not a second try.
  h.Task(22, 1.0, Segment(30, -3, 30, 3));
  h.Tick();
  h.Pose(Pose2(23, 0, 0));  // the face would now be in reach: still the first answer
  h.Task(22, 1.0, Segment(30, -3, 30, 3));
  h.Tick();
  status = h.bus->Decoded<task_status_t>("TASK_STATUS");
  ASSERT_GE(status.size(), 2u);
  EXPECT_EQ(status.back().task_id, 22);
  EXPECT_EQ(status.back().state, task_status_t::FAILED);
  EXPECT_EQ(status.back().message, status[status.size() - 2].message);
  EXPECT_FALSE(h.node.cutter().active());
}

TEST(CutterNodeTest, MalformedTasksAndStatesAreCountedBad) {
  Harness h;
  h.Task(1, 1.0, std::nullopt, 42);  // unknown action
  h.Task(2, 1.0, std::nullopt, cutter_command_t::SHEAR);  // not a task
  cutter_state_t s = ToLcm(CutterState{});
  s.boom_height = std::nan("");
  h.bus->InjectMessage("CUTTER_STATE", s);
  h.Tick();
  EXPECT_EQ(h.bus->counters().messages_bad, 3);
  EXPECT_TRUE(h.bus->PublishedOn("TASK_STATUS").empty());
}

TEST(CutterNodeTest, HelpNamesEveryChannelAndTheCutterOptions) {
  CutterNodeOptions o;
  ConfigSchema schema("cutter", "test");
  DeclareOptions(schema, o);
  const std::string help = schema.HelpText();
  for (const char* channel : {"CUT_TASK", "POSE", "ODOMETRY", "CUTTER_STATE", "CONTOUR_MAP", "DRIVE_COMMAND",
                              "CUTTER_COMMAND", "TASK_STATUS"})
    EXPECT_NE(help.find(channel), std::string::npos) << channel;
  EXPECT_NE(help.find("cutter.sump-step"), std::string::npos) << help;
  EXPECT_EQ(help.find("SIM_TRUTH"), std::string::npos);
}

}  // namespace
}  // namespace minenav
