#include "tracker/testing/closed_loop.h"

#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <random>

#include "common/angle.h"
#include "planner/testing/path_checker.h"
#include "tracker/pure_pursuit.h"

namespace minenav::testing {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000;  // us, the run's clock starts here

struct Nearest {
  double distance = std::numeric_limits<double>::infinity();
  double heading_error = 0.0;
};

// The nearest of all of the run's samples (brute force: the judge shares no search window
// with the tracker).
Nearest NearestOnRun(const TrackedRun& run, const Pose2& truth) {
  Nearest n;
  for (const Pose2& s : run.samples) {
    const double d = TranslationDistance(s, truth);
    if (d < n.distance) {
      n.distance = d;
      n.heading_error = NormalizeAngle(truth.theta - s.theta);
    }
  }
  return n;
}

}  // namespace

ClosedLoopResult RunClosedLoop(const std::vector<Segment>& world, const std::vector<Segment>& map,
                               const PlannedPath& path, const Footprint& footprint, const ClosedLoopOptions& o,
                               std::optional<Pose2> truth_start) {
  ClosedLoopResult result;
  const Pose2 start = truth_start.value_or(path.start);
  SkidSteerVehicle vehicle(o.vehicle, start);
  DeadReckoning odometry(o.odometry, Pose2(), o.seed * 7919 + 1);  // its own frame: starts at the origin
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PosePredictor predictor(o.predictor);
  PathTracker tracker(o.tracker, footprint);
  if (!map.empty())
    tracker.SetMap(std::make_shared<TrackerMap>(map, footprint, o.tracker.collision_margin, o.tracker.turn_radius));
  TrackState state = tracker.SetPath(path);
  const std::vector<TrackedRun> runs = SplitIntoRuns(path, 0.01);
  const Pose2 goal = runs.empty() ? path.start : runs.back().end;
  const std::vector<Eigen::Vector2d> polygon = Normalized(footprint).vertices;

  const double dt = 1.0 / o.sim_rate;
  const int control_every = std::max(1, static_cast<int>(std::lround(o.sim_rate / o.control_rate)));
  std::deque<std::pair<double, PoseEstimate>> pending;
  double next_scan = 0.0;
  DriveCommand command;  // stop
  double sum_ct2 = 0.0, sum_h2 = 0.0;
  int64_t measured = 0;
  result.min_clearance = std::numeric_limits<double>::infinity();
  std::optional<double> finished_at;
  if (state != TrackState::kActive) {
    result.state = state;
    result.message = tracker.message();
    finished_at = 0.0;
  }
  for (int64_t i = 0;; ++i) {
    const double t = static_cast<double>(i) * dt;
    const int64_t utime = kT0 + static_cast<int64_t>(std::llround(t * 1e6));
    if (t > o.max_time || (finished_at && t > *finished_at + 3.0)) break;
    const Pose2 truth = vehicle.pose();
    // A scan now: its estimate arrives pose_latency later.
    if (t + 1e-9 >= next_scan && !(o.pose_outage_at && t >= *o.pose_outage_at)) {
      PoseEstimate e;
      e.utime = utime;
      e.converged = true;
      e.status = "ok";
      e.source = "noisy truth";
      Pose2 noisy(truth.x + o.pose_sigma_xy * gauss(rng), truth.y + o.pose_sigma_xy * gauss(rng),
                  NormalizeAngle(truth.theta + o.pose_sigma_theta * gauss(rng)));
      if (o.pose_jump_at && t >= *o.pose_jump_at && t < o.pose_jump_until) noisy = noisy * o.pose_jump;
      e.pose = noisy;
      e.covariance = Eigen::Vector3d(o.pose_sigma_xy * o.pose_sigma_xy, o.pose_sigma_xy * o.pose_sigma_xy,
                                     o.pose_sigma_theta * o.pose_sigma_theta)
                         .asDiagonal();
      pending.emplace_back(t + o.pose_latency, e);
      next_scan = o.pose_rate > 0.0 ? next_scan + 1.0 / o.pose_rate : std::numeric_limits<double>::infinity();
    }
    if (!o.later_map.empty() && t >= o.later_map_at && t - dt < o.later_map_at)
      tracker.SetMap(std::make_shared<TrackerMap>(o.later_map, footprint, o.tracker.collision_margin,
                                                  o.tracker.turn_radius));
    predictor.AddOdometry(odometry.Reading(utime));
    while (!pending.empty() && pending.front().first <= t + 1e-9) {
      const EstimateVerdict v = predictor.AddEstimate(pending.front().second);
      ++result.estimates;
      if (v.trusted) ++result.trusted;
      if (v.jump) {
        ++result.jumps;
        result.reports.push_back(v.reason);
      }
      pending.pop_front();
    }
    if (i % control_every == 0) {
      const std::optional<Pose2> pose = predictor.Predict();
      if (pose && !finished_at) {
        const TrackStep step = tracker.Update(*pose);
        command = step.command;
        if (step.state != TrackState::kActive) {
          finished_at = t;
          result.state = step.state;
          result.message = step.message;
          result.time = t;
        }
      } else {
        command = DriveCommand();
        command.timeout = o.tracker.command_timeout;
      }
      command.utime = utime;
      result.commands.push_back(command);
    }
    // The judges.
    result.truth.push_back(truth);
    const double clearance = PoseClearance(world, polygon, truth);
    result.min_clearance = std::min(result.min_clearance, clearance);
    if (clearance <= 0.0) result.contact = true;
    const int r = tracker.run_index();
    if (!finished_at && r < static_cast<int>(runs.size()) && runs[static_cast<size_t>(r)].direction != 0) {
      const Nearest n = NearestOnRun(runs[static_cast<size_t>(r)], truth);
      result.cross_track_max = std::max(result.cross_track_max, n.distance);
      result.heading_max = std::max(result.heading_max, std::abs(n.heading_error));
      sum_ct2 += n.distance * n.distance;
      sum_h2 += n.heading_error * n.heading_error;
      ++measured;
    }
    if (o.stop_when && o.stop_when(t, truth)) break;
    // The step, with slip the odometry does not see.
    const MotionIncrement inc = vehicle.Step(dt, command, utime);
    const double ds = std::abs(inc.distance);
    if (ds > 0.0) {
      const Pose2 slip(0.0, o.slip_lateral_sigma * std::sqrt(ds) * gauss(rng),
                       std::copysign(o.slip_heading_per_metre * ds, inc.rotation == 0.0 ? 1.0 : inc.rotation));
      vehicle.set_pose(vehicle.pose() * slip);
    }
    odometry.AddIncrement(inc);
  }
  if (!finished_at) {
    result.state = tracker.state();
    result.message = "cut off after " + std::to_string(o.max_time) + " s: " + tracker.message();
    result.time = o.max_time;
  }
  if (measured > 0) {
    result.cross_track_rms = std::sqrt(sum_ct2 / static_cast<double>(measured));
    result.heading_rms = std::sqrt(sum_h2 / static_cast<double>(measured));
  }
  const Pose2 end = vehicle.pose();
  result.final_position_error = TranslationDistance(end, goal);
  result.final_heading_error = std::abs(NormalizeAngle(end.theta - goal.theta));
  result.corrections = tracker.corrections();
  return result;
}

}  // namespace minenav::testing

#include <chrono>

#include "planner/se2_planner.h"
#include "planner/test_maps.h"
#include "sim/mine_generator.h"

namespace minenav::testing {

const std::vector<std::string>& ScenarioNames() {
  static const std::vector<std::string> names = {"straight_entry", "box_cut", "slab_cut", "intersection_turn"};
  return names;
}

TrackingScenario MakeScenario(const std::string& name, double clearance) { return MakeScenario(name, clearance, {}); }

TrackingScenario MakeScenario(const std::string& name, double clearance,
                              const std::function<void(Se2PlannerOptions&)>& adjust) {
  TrackingScenario s;
  s.name = name;
  MineOptions mine;
  mine.midpoint_displacement = 0.1;
  constexpr double kRoom = 6.0, kPitch = 18.0;
  Se2PlannerOptions po;
  po.clearance = clearance;
  Pose2 start, goal;
  if (name == "intersection_turn" || name == "intersection_turn_6m") {
    s.world = planner_test::Crossing(name == "intersection_turn" ? 6.5 : kRoom, 20.0);
    po.heading_bins = 36;
    po.xy_resolution = 0.2;
    start = Pose2(0, -12, kPi / 2);
    goal = Pose2(12, 0, kPi);
  } else {
    s.world = GenerateRoomAndPillarMine(mine);
    const double face_x = kRoom + kPitch + 12.0 - 1.0;  // across entry 1, 1 m before the crossing
    const double entry1 = 0.5 * kRoom + kPitch;
    if (name == "straight_entry") {
      start = Pose2(8.0, 0.5 * kRoom + 0.3, DegToRad(1.0));
      goal = Pose2(40.0, 0.5 * kRoom, 0.0);
    } else if (name == "box_cut") {
      s.world.push_back({face_x, entry1 - 4.0, face_x, entry1 + 4.0});
      start = Pose2(face_x - 12.6, entry1 + 0.3, 0.0);
      goal = Pose2(face_x - 5.6, entry1, 0.0);
    } else if (name == "slab_cut") {
      s.world.push_back({face_x, entry1 - 4.0, face_x, entry1 + 4.0});
      start = Pose2(face_x - 5.6, entry1 + 0.7, 0.0);
      goal = Pose2(face_x - 5.6, entry1 - 0.7, 0.0);
    } else {
      s.error = "unknown scenario " + name;
      return s;
    }
  }
  if (adjust) adjust(po);
  const Se2Planner planner(s.world, Footprint::Rectangle(3.3, 10.0), po);
  const auto t0 = std::chrono::steady_clock::now();
  const Se2PlanResult r = planner.Plan(start, goal);
  s.plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (r.status != SearchStatus::kFound) {
    s.error = name + ": no path: " + r.reason;
    return s;
  }
  s.path = r.path;
  return s;
}

}  // namespace minenav::testing
