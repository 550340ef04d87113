#pragma once
// The tracker in a closed loop in simulation, for the tracker's tests and bench (this library
// links sim/: never the tracker's own targets). The miner is sim/skid_steer.h's vehicle
// (the kinematics and limits vehicle_sim runs) with dead-reckoned odometry that drifts
// (sim/odometry_model.h, starting at the true start pose as vehicle_sim's) and wheel slip the
// odometry does not see (the true pose turns and slides a little as it drives). A scan is
// taken every 1 / pose_rate s; its pose estimate comes from one of two sources:
//   * kNoisyTruth: the true pose at the scan time plus Gaussian noise, reported with that
//     covariance, delivered `pose_latency` later; the tracker's map is the `map` given;
//   * kLiveMapper: the live contour mapper (mapper_pose_source.h): the simulated ladar scan of
//     the TRUE world from the TRUE pose, mapped with the drifting odometry, inserted every
//     metre or 0.3 rad and tracked otherwise, its estimate delivered when the computation is
//     done. The map starts from a short survey (`survey`: scans from those true poses before
//     the run, the first anchoring the map's frame at the world's) and the first scan at the
//     start, before the path is given; the tracker's map is the mapper's contour map,
//     replaced with each insert (CONTOUR_MAP), as path_tracker's node takes it.
// The tracker predicts with PosePredictor and drives with PathTracker, exactly as
// path_tracker's node wires them.
//
// Judged against the truth: the cross-track and heading error of the true pose from the run
// being tracked (the nearest of the run's dense samples, all of them searched), the final
// true pose against the goal, and the clearance of the true footprint from the TRUE world
// (planner/testing/path_checker.h's brute-force judge) at every simulation step.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/se2_planner.h"
#include "sim/odometry_model.h"
#include "sim/skid_steer.h"
#include "sim/vehicle_sim.h"
#include "tracker/path_tracker.h"
#include "tracker/pose_predictor.h"
#include "sim/testing/mapper_pose_source.h"

namespace minenav::testing {

enum class PoseSource { kNoisyTruth, kLiveMapper };
const char* ToString(PoseSource source);

struct ClosedLoopOptions {
  PoseSource pose_source = PoseSource::kNoisyTruth;
  double pose_rate = 1.0;           // Hz of scans, each giving a pose estimate (0: only the first, at t = 0)
  double pose_latency = 0.0;        // s from the scan to the estimate's arrival (kNoisyTruth)
  double pose_sigma_xy = 0.01;      // m, noise of the pose source (kNoisyTruth)
  double pose_sigma_theta = 0.002;  // rad (kNoisyTruth)
  MapperPoseSourceOptions mapper;   // kLiveMapper (its ladar seed is replaced by the run's seed)
  // kLiveMapper: true poses scanned before the run (SurveyPoses), each with its pose as the
  // odometry: the surveyed map the maneuver is planned in. Empty: the map starts from the
  // first scan at the start.
  std::vector<Pose2> survey;
  double control_rate = 10.0;       // Hz of tracker updates
  double sim_rate = 20.0;           // Hz of simulation steps
  double max_time = 2000.0;         // s, the run is cut off after this
  uint64_t seed = 1;
  SkidSteerOptions vehicle;
  OdometryErrorOptions odometry = VehicleSimOptions().odometry;  // vehicle_sim's drifting odometry
  double slip_heading_per_metre = 0.005;  // rad/m the true heading turns that the odometry misses
  double slip_lateral_sigma = 0.005;      // m/sqrt(m), random sideways slip the odometry misses
  PathTrackerOptions tracker;
  PosePredictorOptions predictor;
  // Faults: from this time (s) on, estimates are offset by `pose_jump` (a mapper that lost
  // itself); and from this time on no estimate arrives at all.
  std::optional<double> pose_jump_at;
  double pose_jump_until = 1e18;  // s, the jump ends here
  Pose2 pose_jump{0.0, 1.0, 0.0};
  std::optional<double> pose_outage_at;
  // The tracker's map is replaced by this one at later_map_at s (a wall the mapper sees late).
  std::vector<Segment> later_map;
  double later_map_at = 1e18;
  // Stop the run early (after the step) when this returns true.
  std::function<bool(double t, const Pose2& truth)> stop_when;
};

struct ClosedLoopResult {
  TrackState state = TrackState::kIdle;
  std::string message;
  double time = 0.0;                  // s until the path ended (or max_time)
  double cross_track_rms = 0.0, cross_track_max = 0.0;   // m, true pose, driving runs
  double heading_rms = 0.0, heading_max = 0.0;           // rad, true heading vs the run's
  double final_position_error = 0.0;  // m, true pose vs goal
  double final_heading_error = 0.0;   // rad
  int corrections = 0;                // turn-in-place corrections of the tracker
  double min_clearance = 0.0;         // m, true footprint to the true world, over the run
  bool contact = false;
  int estimates = 0, trusted = 0, jumps = 0;
  // The estimates against the truth at their scans (m, rad), and their latency (s from the
  // scan to the estimate's arrival); with the live mapper its scans' outcomes.
  double estimate_error_rms = 0.0, estimate_error_max = 0.0, estimate_heading_error_max = 0.0;
  double latency_median = 0.0, latency_max = 0.0;
  int scans_inserted = 0, scans_tracked = 0, scans_refused = 0;
  int map_updates = 0;                // tracker maps from the live mapper
  std::vector<std::string> reports;   // the predictor's jump reports
  std::vector<Pose2> truth;           // true poses at every simulation step
  std::vector<DriveCommand> commands; // with utime = us since the start
};

// Drives `path` from the true start `truth_start` (path.start when nullopt) on `map` (what
// the tracker knows with kNoisyTruth; with kLiveMapper it is the mapper's map) in the true
// world `world`.
ClosedLoopResult RunClosedLoop(const std::vector<Segment>& world, const std::vector<Segment>& map,
                               const PlannedPath& path, const Footprint& footprint, const ClosedLoopOptions& options,
                               std::optional<Pose2> truth_start = std::nullopt);

}  // namespace minenav::testing

namespace minenav::testing {

// A short survey along `path`: its start, a pose every `spacing` m along it, and its end.
std::vector<Pose2> SurveyPoses(const PlannedPath& path, double spacing);

// The maneuvers of the tracker's tests and bench, planned by the SE(2) planner
// (planner/se2_planner.h) for the 3.3 x 10 m miner with `clearance` (m):
//   straight_entry     32 m along the south entry of a generated room-and-pillar mine
//                      (sim/mine_generator.h: 12 m pillars, 6 m entries, walls displaced up
//                      to 0.2 m), starting 0.3 m off the centre line and 1 deg off;
//   box_cut            7 m up to a coal face across an entry, from 0.3 m off its centre line;
//   slab_cut           at the same face, 1.4 m across it (a multi-point maneuver with reversals);
//   intersection_turn  from an entry into a crosscut, ending faced back (backing round the
//                      corner: the planner's multi-point maneuver) at a crossing of two
//                      6.5 m entries;
//   intersection_turn_6m  the same at 6 m entries: the planner finds it only with clearance 0,
//                      centimetres from the pillar corners.
struct TrackingScenario {
  std::string name;
  std::vector<Segment> world;  // the true world (= the tracker's map in the tests)
  PlannedPath path;
  std::string error;           // "" when the planner found the path
  double plan_seconds = 0.0;
};
const std::vector<std::string>& ScenarioNames();
TrackingScenario MakeScenario(const std::string& name, double clearance);
// The same with the planner's options changed by `adjust` after the scenario's own (other
// path shapes for one maneuver: the tracker must follow any feasible path).
TrackingScenario MakeScenario(const std::string& name, double clearance,
                              const std::function<void(Se2PlannerOptions&)>& adjust);

}  // namespace minenav::testing
