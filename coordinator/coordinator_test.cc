// The coordinator against a scripted fleet (no bus, no clock): a task planner that proposes
// stations then says the section is explored and plans an advance, a path planner that answers
// every request, a tracker that drives a path in a set time, a cutter that cuts in a set time,
// heartbeats from every process; each test breaks one of them and checks what the coordinator
// does about it.

#include "coordinator/coordinator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace minenav {
namespace {

constexpr int64_t kStep = 100'000;  // us: the coordinator's tick (10 Hz)

CoordinatorOptions Options() {
  CoordinatorOptions o;
  o.required = "mapper,planner,tracker,tasks,cutter";
  o.face = "40,3,0";
  o.depth = 1.0;
  o.station_dwell = 1.0;
  o.resend_period = 1.0;
  o.answer_timeout = 10.0;
  o.ready_timeout = 20.0;
  o.heartbeat_timeout = 3.0;
  o.recovery_timeout = 15.0;
  o.auto_start = true;
  return o;
}

Task MakeTask(int64_t id, TaskKind kind, Pose2 target, const std::string& what) {
  Task t;
  t.id = id;
  t.kind = kind;
  t.target = target;
  t.description = what;
  if (IsCutTask(kind)) {
    t.depth = 1.0;
    t.width = 3.3;
    t.face = Segment(target.x + 5.1, target.y - 1.65, target.x + 5.1, target.y + 1.65);
    t.appendages = Appendages::kCutting;
  } else {
    t.appendages = Appendages::kStowed;
  }
  return t;
}

// The advance of Figure 40 in an entry along x, face at x = 40.
std::vector<Task> AdvancePlan() {
  return {MakeTask(101, TaskKind::kMove, {34.9, 1.6, 0}, "into position"),
          MakeTask(102, TaskKind::kBoxCut, {34.9, 1.6, 0}, "box cut"),
          MakeTask(103, TaskKind::kMove, {34.9, 4.4, 0}, "reposition"),
          MakeTask(104, TaskKind::kSlabCut, {34.9, 4.4, 0}, "slab cut"),
          MakeTask(105, TaskKind::kBackOut, {22.0, 3.0, 0}, "back out")};
}

// A fleet that does what it is asked, with knobs to break it.
struct FakeFleet {
  Coordinator& c;
  int64_t now = 0;
  Pose2 vehicle{2.0, 3.0, 0.0};
  std::vector<Pose2> stations = {{10, 3, 0}, {20, 3, 0}, {30, 3, 0}};
  size_t next_station = 0;
  double drive_time = 5.0, cut_time = 8.0;
  std::set<std::string> dead;                 // processes that send no heartbeat
  std::map<std::string, int> pids;            // each process's pid in its heartbeats (default 100)
  int drop_path_requests = 0, drop_forwards = 0, drop_cut_tasks = 0;
  std::set<int64_t> fail_drives_of_goal_x;    // drives to these x fail once each
  std::set<int64_t> failed_once;
  std::set<int64_t> unreachable_x;            // path requests to these x are infeasible
  int fail_surveys = 0;                       // the first survey requests answered FAILED
  bool cutter_drum_on = false;
  double first_cut_side_shift = 0.0;          // m the first cut leaves the vehicle to its left
  // What the fleet saw.
  std::vector<PathRequestOut> path_requests;
  std::map<int64_t, int> forwards;            // request id -> times received
  std::map<int64_t, int> cut_received;
  std::vector<CutTaskOut> cuts;
  std::vector<int64_t> canceled_paths;
  std::vector<TaskRequest> task_requests;
  int stops = 0;
  std::vector<std::string> log;
  // In flight.
  struct Job { int64_t id; int64_t done_at; Pose2 end; bool fail; bool cut; };
  std::vector<Job> jobs;
  std::map<int64_t, PathRequestOut> answered;

  explicit FakeFleet(Coordinator& coordinator) : c(coordinator) {}

  void Heartbeats() {
    if (now % 1'000'000 != 0) return;
    for (const std::string p : {"mapper", "planner", "tracker", "tasks", "cutter"}) {
      if (dead.count(p)) continue;
      HeartbeatSample hb;
      hb.process = p;
      hb.state = HeartbeatState::kOk;
      hb.pid = pids.count(p) ? pids.at(p) : 100;
      c.OnHeartbeat(hb, now);
    }
  }

  void Status(int64_t id, TaskState st, const std::string& msg, double progress = 0.0) {
    TaskStatusReport r;
    r.task_id = id;
    r.state = st;
    r.message = msg;
    r.progress = progress;
    c.OnTaskStatus(r, now);
  }

  void Serve(const CoordinatorOutputs& out) {
    log.insert(log.end(), out.log.begin(), out.log.end());
    if (out.stop_vehicle) ++stops;
    for (const TaskRequest& q : out.task_requests) {
      task_requests.push_back(q);
      TaskPlan p;
      if (q.kind == TaskRequestKind::kSurveyNext) {
        if (fail_surveys > 0) {
          --fail_surveys;
          p.status = PlanStatus::kFailed;
          p.reason = "deadline: planning was stopped at 5.000 s: no station found within the plan budget";
        } else if (next_station < stations.size()) {
          p.status = PlanStatus::kOk;
          p.tasks = {MakeTask(900 + static_cast<int64_t>(next_station), TaskKind::kScanStation,
                              stations[next_station], "station")};
          p.reason = "frontier";
          ++next_station;
        } else {
          p.status = PlanStatus::kComplete;
          p.reason = "no reachable frontier";
        }
      } else {
        p.status = PlanStatus::kOk;
        p.tasks = AdvancePlan();
        p.reason = "box cut on the left, slab on the right";
      }
      c.OnTaskPlan(q.request_id, p, now);
    }
    for (const PathRequestOut& r : out.path_requests) {
      path_requests.push_back(r);
      if (drop_path_requests > 0) {
        --drop_path_requests;
        continue;
      }
      PathAnswer a;
      a.request_id = r.request_id;
      a.utime = now;
      a.start = r.start;
      a.feasible = !unreachable_x.count(std::llround(r.goal.x));
      a.status = a.feasible ? "ok" : "not reachable";
      answered[r.request_id] = r;
      c.OnPath(a, now);
    }
    for (const int64_t id : out.forward_paths) {
      ++forwards[id];
      if (drop_forwards > 0) {
        --drop_forwards;
        continue;
      }
      if (forwards[id] > 1 && std::any_of(jobs.begin(), jobs.end(), [id](const Job& j) { return j.id == id; })) {
        Status(id, TaskState::kActive, "repeat");  // the tracker's acknowledgement of a repeat
        continue;
      }
      const PathRequestOut& r = answered.at(id);
      const int64_t gx = std::llround(r.goal.x);
      const bool fail = fail_drives_of_goal_x.count(gx) && !failed_once.count(gx);
      if (fail) failed_once.insert(gx);
      jobs.push_back({id, now + std::llround(drive_time * 1e6), r.goal, fail, false});
      Status(id, TaskState::kActive, "taken");
    }
    for (const int64_t id : out.cancel_paths) {
      canceled_paths.push_back(id);
      jobs.erase(std::remove_if(jobs.begin(), jobs.end(), [id](const Job& j) { return j.id == id; }), jobs.end());
      Status(id, TaskState::kCanceled, "canceled by the sender");
    }
    for (const CutTaskOut& t : out.cut_tasks) {
      if (t.cancel) {
        jobs.erase(std::remove_if(jobs.begin(), jobs.end(), [&t](const Job& j) { return j.id == t.id; }), jobs.end());
        Status(t.id, TaskState::kCanceled, "canceled");
        continue;
      }
      cuts.push_back(t);
      if (drop_cut_tasks > 0) {
        --drop_cut_tasks;
        continue;
      }
      if (cut_received[t.id]++ > 0) {
        Status(t.id, TaskState::kActive, "repeat");
        continue;
      }
      Pose2 end = vehicle;
      end.x -= 0.4;  // the cutter backs out of the cut
      if (cut_received.size() == 1) end.y += first_cut_side_shift;
      jobs.push_back({t.id, now + std::llround(cut_time * 1e6), end, false, true});
      Status(t.id, TaskState::kActive, "sumping", 0.0);
    }
  }

  void Progress() {
    for (auto it = jobs.begin(); it != jobs.end();) {
      if (now >= it->done_at) {
        if (it->fail) {
          Status(it->id, TaskState::kFailed, "blocked: a wall ahead");
        } else {
          vehicle = it->end;
          Status(it->id, TaskState::kDone, "done");
        }
        it = jobs.erase(it);
      } else {
        if (it->cut) {
          const double left = static_cast<double>(it->done_at - now) / (cut_time * 1e6);
          Status(it->id, TaskState::kActive, "sumping", 1.0 - left);
        }
        ++it;
      }
    }
  }

  // The tracker killed and restarted by its supervisor between two heartbeats: a new pid,
  // and the path it was driving forgotten (no status for it ever again).
  void RestartTracker() {
    pids["tracker"] = (pids.count("tracker") ? pids.at("tracker") : 100) + 1;
    jobs.erase(std::remove_if(jobs.begin(), jobs.end(), [](const Job& j) { return !j.cut; }), jobs.end());
    for (auto& [id, n] : forwards) n = 0;  // the new tracker has seen no path
  }

  // One tick of 100 ms: heartbeats, the pose, the coordinator, the fleet's answers.
  void Step() {
    now += kStep;
    Heartbeats();
    Progress();
    if (!dead.count("mapper")) c.OnPose(vehicle, now, now);
    c.OnCutterState(cutter_drum_on, !cutter_drum_on, now);
    c.Tick(now);
    Serve(c.TakeOutputs());
  }

  void RunFor(double seconds) {
    const int64_t end = now + std::llround(seconds * 1e6);
    while (now < end) Step();
  }
  bool RunUntilFinished(double max_seconds) {
    const int64_t end = now + std::llround(max_seconds * 1e6);
    while (now < end && !c.Finished()) Step();
    return c.Finished();
  }
  bool Logged(const std::string& what) const {
    return std::any_of(log.begin(), log.end(), [&](const std::string& l) { return l.find(what) != std::string::npos; });
  }
};

void StartMission(Coordinator& c, FakeFleet& f) {
  ASSERT_EQ(c.OnOperator(OperatorCommand::kStart, 1, f.now), "");
}

TEST(CoordinatorTest, TheWholeMissionExploresThenAdvancesTheEntry) {
  Coordinator c(Options(), 1000);
  FakeFleet f(c);
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600)) << c.Status().message;
  EXPECT_EQ(c.state(), MissionState::kDone) << c.Status().message;
  // Three stations, then the planner's COMPLETE, then one advance request.
  ASSERT_EQ(f.task_requests.size(), 5u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(f.task_requests[static_cast<size_t>(i)].kind, TaskRequestKind::kSurveyNext);
  EXPECT_EQ(f.task_requests[4].kind, TaskRequestKind::kAdvance);
  EXPECT_DOUBLE_EQ(f.task_requests[4].face.x, 40.0);
  EXPECT_DOUBLE_EQ(f.task_requests[4].depth, 1.0);
  EXPECT_EQ(c.stats().stations_visited, 3);
  // Both cuts, each with its face and depth, box before slab.
  ASSERT_EQ(f.cuts.size(), 2u);
  EXPECT_NEAR(f.cuts[0].face.a.y(), 1.6 - 1.65, 1e-9);
  EXPECT_NEAR(f.cuts[1].face.a.y(), 4.4 - 1.65, 1e-9);
  EXPECT_DOUBLE_EQ(f.cuts[0].depth, 1.0);
  // The vehicle ended where the back-out put it.
  EXPECT_NEAR(f.vehicle.x, 22.0, 1e-9);
  const MissionStatus s = c.Status();
  EXPECT_EQ(s.tasks_total, 5);
  EXPECT_EQ(s.tasks_done, 5);
  EXPECT_EQ(s.state, MissionState::kDone);
}

TEST(CoordinatorTest, TheNextSubtasksPathIsPlannedWhileTheCutRuns) {
  Coordinator c(Options(), 1000);
  FakeFleet f(c);
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  // The reposition after the box cut and the back-out after the slab cut were planned during
  // the cuts: their paths went to the tracker the tick they started.
  EXPECT_EQ(c.stats().drives_preplanned, 2) << "drives " << c.stats().drives;
  const std::vector<double>& waits = c.stats().planning_waits;
  EXPECT_EQ(std::count_if(waits.begin(), waits.end(), [](double w) { return w == 0.0; }), 2)
      << "a fresh path takes at least a tick (the planner answers between ticks)";
  // The pre-planned requests started where the cuts would end: backed out, 0.4 m behind their target.
  int ahead = 0;
  for (const PathRequestOut& r : f.path_requests)
    if (std::abs(r.start.x - (34.9 - 0.4)) < 1e-9 && (std::abs(r.start.y - 1.6) < 1e-9 || std::abs(r.start.y - 4.4) < 1e-9))
      ++ahead;
  EXPECT_EQ(ahead, 2);
}

// At real speed a cut keeps the next subtask's path waiting: one planned ahead longer ago than
// preplan_max_age is planned anew rather than sent to a tracker that abandons old paths (the
// 53-minute mission of 2026-12-07 lost a drive to "path stale: planned 600.09 s ago").
TEST(CoordinatorTest, APathPlannedAheadTooLongAgoIsPlannedAnew) {
  CoordinatorOptions o = Options();
  o.explore = false;
  o.preplan_max_age = 5.0;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.cut_time = 8.0;  // each cut outlasts the age limit
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_EQ(c.stats().drives_preplanned, 0);
  EXPECT_TRUE(f.Logged("s ago, over preplan_max_age")) << "and says why";
}

TEST(CoordinatorTest, APathPlannedAheadIsNotUsedWhenTheVehicleEndsElsewhere) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.first_cut_side_shift = 0.6;  // the box cut leaves the vehicle 0.6 m from where the plan assumed
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_EQ(c.stats().drives_preplanned, 1) << "the slab cut's back-out only";
  EXPECT_TRUE(f.Logged("the path planned ahead is not used")) << "and says why";
}

TEST(CoordinatorTest, NothingStartsUntilEveryRequiredProcessIsReady) {
  CoordinatorOptions o = Options();
  o.ready_timeout = 5.0;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.dead = {"cutter"};
  StartMission(c, f);
  f.RunFor(2.0);
  EXPECT_EQ(c.state(), MissionState::kWaiting);
  EXPECT_EQ(c.Status().waiting_for, "cutter: never seen");
  EXPECT_TRUE(f.task_requests.empty() && f.path_requests.empty());
  ASSERT_TRUE(f.RunUntilFinished(10));
  EXPECT_EQ(c.state(), MissionState::kFailed);
  EXPECT_NE(c.Status().message.find("not ready within 5 s: cutter: never seen"), std::string::npos)
      << c.Status().message;
}

TEST(CoordinatorTest, UnacknowledgedCommandsAreResentAndRepeatsDoNoHarm) {
  Coordinator c(Options(), 1000);
  FakeFleet f(c);
  f.drop_path_requests = 2;
  f.drop_forwards = 1;
  f.drop_cut_tasks = 1;
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_GE(c.stats().resends, 4);
  // The first path request was sent three times (two lost) under one id.
  ASSERT_GE(f.path_requests.size(), 3u);
  EXPECT_EQ(f.path_requests[0].request_id, f.path_requests[1].request_id);
  EXPECT_EQ(f.path_requests[1].request_id, f.path_requests[2].request_id);
  // Each path was driven once however often it was sent; the lost cut task was sent again.
  int repeated = 0;
  for (const auto& [id, n] : f.forwards) repeated += n > 1;
  EXPECT_EQ(repeated, 1);
  EXPECT_EQ(f.cuts.size(), 3u);
  EXPECT_EQ(f.cut_received.size(), 2u);
}

TEST(CoordinatorTest, AFailedDriveIsPlannedAnewFromWhereTheVehicleIs) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.fail_drives_of_goal_x = {35};  // into position fails once
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_EQ(c.stats().retries, 1);
  std::vector<int64_t> ids;
  for (const PathRequestOut& r : f.path_requests)
    if (std::llround(r.goal.x) == 35 && std::abs(r.goal.y - 1.6) < 1e-9) ids.push_back(r.request_id);
  ASSERT_EQ(ids.size(), 2u);
  EXPECT_NE(ids[0], ids[1]) << "a new request, not the old one again";
  EXPECT_TRUE(f.Logged("retrying 'into position' (attempt 2) in 3 s"));
}

TEST(CoordinatorTest, StationsThatCannotBeReachedEndTheExplorationWithTheReason) {
  CoordinatorOptions o = Options();
  o.max_failed_stations = 2;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.stations = {{10, 3, 0}, {50, 3, 0}, {60, 3, 0}};
  f.unreachable_x = {50, 60};
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kFailed);
  EXPECT_EQ(c.stats().stations_visited, 1);
  EXPECT_EQ(c.stats().stations_failed, 2);
  EXPECT_NE(c.Status().message.find("2 stations in a row not reached; the last: no path to (60.00, 3.00"),
            std::string::npos)
      << c.Status().message;
  EXPECT_GE(f.stops, 1) << "the vehicle is told to stop";
}

TEST(CoordinatorTest, AStationNotDecidedIsAskedForAgainAfterTheRetryDelay) {
  // The task planner's FAILED (its deadline spent before a station was found) is asked again
  // after retry_delay, and the mission goes on.
  CoordinatorOptions o = Options();
  o.retry_delay = 3.0;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.fail_surveys = 2;
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone) << c.Status().message;
  EXPECT_EQ(c.stats().stations_visited, 3);
  // Two FAILED answers, three stations, the COMPLETE one and the advance.
  ASSERT_EQ(f.task_requests.size(), 7u);
  int events = 0;
  for (const std::string& e : c.stats().events) events += e.rfind("no station decided (task planner: deadline", 0) == 0;
  EXPECT_EQ(events, 2);
}

TEST(CoordinatorTest, StationsNotDecidedEndTheExplorationWithTheReason) {
  CoordinatorOptions o = Options();
  o.max_failed_stations = 2;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.fail_surveys = 5;
  StartMission(c, f);
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kFailed);
  EXPECT_EQ(f.task_requests.size(), 2u);
  EXPECT_NE(c.Status().message.find("2 stations in a row not reached or not decided; the last: task planner: deadline"),
            std::string::npos)
      << c.Status().message;
}

TEST(CoordinatorTest, ALostProcessStopsTheVehicleAndTheMissionGoesOnWhenItIsBack) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.drive_time = 20.0;
  StartMission(c, f);
  f.RunFor(5.0);
  ASSERT_EQ(f.forwards.size(), 1u) << "the first drive is under way";
  const int64_t first = f.forwards.begin()->first;
  f.dead = {"tracker"};
  f.RunFor(4.5);
  EXPECT_EQ(c.state(), MissionState::kWaiting);
  EXPECT_EQ(f.canceled_paths, std::vector<int64_t>{first});
  EXPECT_NE(c.Status().waiting_for.find("tracker: no heartbeat for"), std::string::npos);
  const int stops = f.stops;
  f.RunFor(2.0);
  EXPECT_GT(f.stops, stops) << "stop commands go on while it is lost";
  f.dead.clear();
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_EQ(c.stats().pauses_for_lost_processes, 1);
  EXPECT_EQ(c.stats().retries, 0) << "a halt is not a failed attempt";
}

// The supervisor restarts a killed tracker before its silence reaches the heartbeat timeout:
// the coordinator knows it by the new pid, halts the drive and starts it again (a new path
// from where the vehicle is); without that it would wait for the forgotten path forever.
TEST(CoordinatorTest, ATrackerRestartedBetweenHeartbeatsGetsTheDriveAgain) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.drive_time = 20.0;
  StartMission(c, f);
  f.RunFor(5.0);
  ASSERT_EQ(f.forwards.size(), 1u) << "the first drive is under way";
  const int64_t first = f.forwards.begin()->first;
  f.RestartTracker();
  ASSERT_TRUE(f.RunUntilFinished(600));
  EXPECT_EQ(c.state(), MissionState::kDone);
  EXPECT_TRUE(f.Logged("restarted: tracker (pid 101, was 100)")) << "the log says why";
  EXPECT_EQ(f.canceled_paths, std::vector<int64_t>{first});
  EXPECT_EQ(c.stats().pauses_for_lost_processes, 1);
  EXPECT_EQ(c.stats().retries, 0) << "a restart is not a failed attempt";
}

TEST(CoordinatorTest, AProcessThatDoesNotComeBackFailsTheMissionSafely) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  StartMission(c, f);
  f.RunFor(5.0);
  f.dead = {"planner"};
  ASSERT_TRUE(f.RunUntilFinished(60));
  EXPECT_EQ(c.state(), MissionState::kFailed);
  EXPECT_NE(c.Status().message.find("planner: no heartbeat for"), std::string::npos);
  EXPECT_NE(c.Status().message.find("not back within 15 s"), std::string::npos);
}

TEST(CoordinatorTest, TheOperatorPausesResumesAbortsAndStops) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.drive_time = 30.0;
  StartMission(c, f);
  EXPECT_EQ(c.OnOperator(OperatorCommand::kStart, 2, f.now), "the mission is already started");
  f.RunFor(5.0);
  ASSERT_EQ(f.forwards.size(), 1u);
  EXPECT_EQ(c.OnOperator(OperatorCommand::kPause, 3, f.now), "");
  f.Step();
  EXPECT_EQ(c.state(), MissionState::kPaused);
  EXPECT_EQ(f.canceled_paths.size(), 1u);
  const size_t requests = f.path_requests.size();
  f.RunFor(5.0);
  EXPECT_EQ(f.path_requests.size(), requests) << "nothing new while paused";
  EXPECT_EQ(c.OnOperator(OperatorCommand::kResume, 4, f.now), "");
  EXPECT_EQ(c.OnOperator(OperatorCommand::kResume, 4, f.now), "") << "a repeat is ignored";
  f.RunFor(3.0);
  EXPECT_EQ(c.state(), MissionState::kRunning);
  EXPECT_EQ(f.path_requests.size(), requests + 1) << "the halted drive planned anew from where the vehicle is";
  // E-stop: a STOP every tick until resumed or aborted.
  EXPECT_EQ(c.OnOperator(OperatorCommand::kEstop, 5, f.now), "");
  const int stops = f.stops;
  f.RunFor(1.0);
  EXPECT_EQ(c.state(), MissionState::kEstopped);
  EXPECT_EQ(f.stops - stops, 10);
  EXPECT_EQ(c.OnOperator(OperatorCommand::kStart, 6, f.now), "e-stopped: resume or abort first");
  EXPECT_EQ(c.OnOperator(OperatorCommand::kAbort, 7, f.now), "");
  EXPECT_EQ(c.state(), MissionState::kAborted);
  EXPECT_EQ(c.Status().message, "aborted by the operator");
  EXPECT_EQ(c.OnOperator(OperatorCommand::kPause, 8, f.now), "nothing to pause");
}

TEST(CoordinatorTest, TheMinerDoesNotTramWithTheDrumTurning) {
  CoordinatorOptions o = Options();
  o.explore = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.cutter_drum_on = true;
  StartMission(c, f);
  f.RunFor(5.0);
  EXPECT_TRUE(f.path_requests.empty());
  EXPECT_NE(c.Status().waiting_for.find("appendages stowed"), std::string::npos) << c.Status().waiting_for;
  f.cutter_drum_on = false;
  f.RunFor(1.0);
  EXPECT_EQ(f.path_requests.size(), 1u);
}

TEST(CoordinatorTest, AHaltedCutGoesOnWithTheDepthThatRemains) {
  CoordinatorOptions o = Options();
  o.explore = false;
  o.preplan = false;
  Coordinator c(o, 1000);
  FakeFleet f(c);
  f.cut_time = 10.0;
  StartMission(c, f);
  while (f.cuts.empty() && f.now < 60'000'000) f.Step();
  ASSERT_EQ(f.cuts.size(), 1u);
  f.RunFor(4.05);  // 40 % of the cut
  ASSERT_EQ(c.OnOperator(OperatorCommand::kPause, 2, f.now), "");
  f.Step();
  ASSERT_EQ(c.OnOperator(OperatorCommand::kResume, 3, f.now), "");
  f.RunFor(1.0);
  ASSERT_EQ(f.cuts.size(), 2u) << "the cut, then the rest of it";
  const CutTaskOut& rest = f.cuts.back();
  EXPECT_NE(rest.id, f.cuts.front().id);
  EXPECT_NEAR(rest.depth, 0.6, 0.02);
  EXPECT_NEAR(rest.face.a.x() - f.cuts.front().face.a.x(), 0.4, 0.02) << "the face as far as it was cut";
}

}  // namespace
}  // namespace minenav
