#include "sim/testing/tracker_closed_loop.h"

#include <algorithm>
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

const char* ToString(PoseSource source) {
  return source == PoseSource::kLiveMapper ? "live mapper" : "noisy truth";
}

ClosedLoopResult RunClosedLoop(const std::vector<Segment>& world, const std::vector<Segment>& map,
                               const PlannedPath& path, const Footprint& footprint, const ClosedLoopOptions& o,
                               std::optional<Pose2> truth_start) {
  ClosedLoopResult result;
  const Pose2 start = truth_start.value_or(path.start);
  SkidSteerVehicle vehicle(o.vehicle, start);
  DeadReckoning odometry(o.odometry, start, o.seed * 7919 + 1);  // as vehicle_sim's: from the start pose
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PosePredictor predictor(o.predictor);
  PathTracker tracker(o.tracker, footprint);
  auto set_map = [&](const std::vector<Segment>& segments) {
    tracker.SetMap(std::make_shared<TrackerMap>(segments, footprint, o.tracker.collision_margin, o.tracker.turn_radius));
  };
  const bool live = o.pose_source == PoseSource::kLiveMapper;
  std::optional<MapperPoseSource> mapper;
  std::optional<StaticSegmentIndex> world_index;
  if (live) {
    MapperPoseSourceOptions mo = o.mapper;
    mo.seed = o.seed;
    mapper.emplace(mo);
    world_index.emplace(world);
  }
  // Estimates (and with the live mapper its maps) on their way, in order of arrival.
  struct Pending {
    double at = 0.0;
    PoseEstimate estimate;
    Pose2 truth;  // at the scan
    bool map = false;
    std::vector<Segment> segments;
  };
  std::deque<Pending> pending;
  std::vector<double> latencies;
  double sum_e2 = 0.0;
  int judged_estimates = 0;
  // A scan at t: its estimate (and map) go on their way.
  auto scan = [&](double t, int64_t utime, const Pose2& truth) {
    Pending p;
    p.truth = truth;
    if (live) {
      const MapperPoseSource::Output out = mapper->Scan(*world_index, truth, odometry.pose(), utime, t);
      p.at = out.ready_at;
      p.estimate = out.estimate;
      result.scans_inserted += out.outcome == mapper::ScanOutcome::kInserted;
      result.scans_tracked += out.outcome == mapper::ScanOutcome::kTracked;
      result.scans_refused += out.outcome == mapper::ScanOutcome::kRefused;
      if (out.map_changed) {
        p.map = true;
        p.segments = mapper->MapSegments();
      }
    } else {
      p.at = t + o.pose_latency;
      PoseEstimate& e = p.estimate;
      e.utime = utime;
      e.converged = true;
      e.status = "ok";
      e.source = "noisy truth";
      e.pose = Pose2(truth.x + o.pose_sigma_xy * gauss(rng), truth.y + o.pose_sigma_xy * gauss(rng),
                     NormalizeAngle(truth.theta + o.pose_sigma_theta * gauss(rng)));
      e.covariance = Eigen::Vector3d(o.pose_sigma_xy * o.pose_sigma_xy, o.pose_sigma_xy * o.pose_sigma_xy,
                                     o.pose_sigma_theta * o.pose_sigma_theta)
                         .asDiagonal();
    }
    if (o.pose_jump_at && t >= *o.pose_jump_at && t < o.pose_jump_until) p.estimate.pose = p.estimate.pose * o.pose_jump;
    latencies.push_back(p.at - t);
    pending.push_back(std::move(p));
  };

  double next_scan = 0.0;
  if (live) {
    // The surveyed map, then what the first scan at the start adds, before the path is given.
    for (size_t k = 0; k < o.survey.size(); ++k) {
      const double t = -10.0 * static_cast<double>(o.survey.size() - k);
      mapper->Scan(*world_index, o.survey[k], o.survey[k], kT0 + static_cast<int64_t>(t * 1e6), t);
    }
    scan(0.0, kT0, start);
    set_map(mapper->MapSegments());
    ++result.map_updates;
    pending.back().map = false;
    next_scan = o.pose_rate > 0.0 ? 1.0 / o.pose_rate : std::numeric_limits<double>::infinity();
  } else if (!map.empty()) {
    set_map(map);
  }
  TrackState state = tracker.SetPath(path);
  const std::vector<TrackedRun> runs = SplitIntoRuns(path, 0.01);
  const Pose2 goal = runs.empty() ? path.start : runs.back().end;
  const std::vector<Eigen::Vector2d> polygon = Normalized(footprint).vertices;

  const double dt = 1.0 / o.sim_rate;
  const int control_every = std::max(1, static_cast<int>(std::lround(o.sim_rate / o.control_rate)));
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
    // A scan now: its estimate arrives later.
    if (t + 1e-9 >= next_scan && !(o.pose_outage_at && t >= *o.pose_outage_at)) {
      scan(t, utime, truth);
      next_scan = o.pose_rate > 0.0 ? next_scan + 1.0 / o.pose_rate : std::numeric_limits<double>::infinity();
    }
    if (!o.later_map.empty() && t >= o.later_map_at && t - dt < o.later_map_at) set_map(o.later_map);
    predictor.AddOdometry(odometry.Reading(utime));
    while (!pending.empty() && pending.front().at <= t + 1e-9) {
      const Pending& p = pending.front();
      if (p.map) {
        set_map(p.segments);
        ++result.map_updates;
      }
      if (p.estimate.converged) {
        const double e = TranslationDistance(p.estimate.pose, p.truth);
        sum_e2 += e * e;
        ++judged_estimates;
        result.estimate_error_max = std::max(result.estimate_error_max, e);
        result.estimate_heading_error_max =
            std::max(result.estimate_heading_error_max, std::abs(NormalizeAngle(p.estimate.pose.theta - p.truth.theta)));
      }
      const EstimateVerdict v = predictor.AddEstimate(p.estimate);
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
  if (judged_estimates > 0) result.estimate_error_rms = std::sqrt(sum_e2 / judged_estimates);
  if (!latencies.empty()) {
    std::sort(latencies.begin(), latencies.end());
    result.latency_median = latencies[latencies.size() / 2];
    result.latency_max = latencies.back();
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

std::vector<Pose2> SurveyPoses(const PlannedPath& path, double spacing) {
  std::vector<Pose2> poses = {path.start};
  double since = 0.0;
  for (const TrackedRun& run : SplitIntoRuns(path, 0.1)) {
    for (size_t k = 1; k < run.samples.size(); ++k) {
      since += TranslationDistance(run.samples[k - 1], run.samples[k]);
      if (since >= spacing) {
        poses.push_back(run.samples[k]);
        since = 0.0;
      }
    }
  }
  if (!path.pieces.empty() && TranslationDistance(poses.back(), path.pieces.back().end) > 1e-6)
    poses.push_back(path.pieces.back().end);
  return poses;
}

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
