#pragma once
// A survey in simulation, for the task planner's tests and bench (this library links sim/,
// the ladar simulation and the mapper: never the planner's own targets). A true world of
// segments; 360-degree scans ray-cast from the true pose (the Typhoon model, range cut to
// `sensor_range`, `scan_points` readings); the contour mapper (mapper/contour_mapper.h) inserting each with its true
// pose as the initial estimate; the task planner choosing each next station on the mapper's
// contour map (PlanNextStation) until it answers COMPLETE (or FAILED, or max_stations).
//
// Judged against the truth: the known free space of the final map (KnownFreeSpace on a grid of
// `coverage_cell`) against the true free space (sim/world.h's parity test from `inside`).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "mapper/contour_mapper.h"
#include "planner/footprint.h"
#include "planner/se2_planner.h"
#include "planner/survey_planner.h"
#include "planner/task.h"
#include "planner/task_map.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/world.h"

namespace minenav::testing {

// The true world and the mapper that maps it from simulated scans at true poses.
class SurveySimulation {
 public:
  // `scan_points` readings per revolution (the Typhoon's 2048 by default).
  SurveySimulation(std::vector<Segment> world, double sensor_range, int scan_points = 2048, uint64_t seed = 7);
  // A scan at the true pose, inserted with the true pose as its initial estimate: "" when
  // the mapper accepted it, else its reason.
  std::string ScanAt(const Pose2& pose);
  // The mapper's contour map: walls and frontiers.
  TaskMap Map() const;
  // Fraction of a true scan from `pose` whose points lie within 0.3 m of `map`'s walls: how
  // much of what the ladar would really see there the map already holds.
  double TrueOverlap(const TaskMap& map, const Pose2& pose) const;

  const World& world() const { return world_; }
  const std::vector<Segment>& truth() const { return truth_; }
  const mapper::ContourMapper& mapper() const { return mapper_; }

 private:
  World world_;
  std::vector<Segment> truth_;
  StaticSegmentIndex index_;
  LadarSimulator simulator_;
  mapper::ContourMapper mapper_;
  int64_t scans_ = 0;
};

struct SurveyExplorationOptions {
  Footprint footprint = Footprint::Rectangle(1.2, 2.0);  // the vehicle
  Pose2 start;                                           // the first station (scanned before the first decision)
  Eigen::Vector2d inside = Eigen::Vector2d::Zero();      // a truly free point (the coverage's reference)
  int scan_points = 2048;       // readings per scan
  double sensor_range = 15.0;                            // m
  double clearance = 0.1;                                // m, the requests'
  int max_stations = 40;
  double coverage_cell = 0.25;  // m
  SurveyPlannerOptions survey;
  Se2PlannerOptions planner;
};

// One decision of the survey.
struct SurveyStep {
  int index = 0;  // 1, 2, ...
  TaskMap map;    // the map it was made on
  SurveyRequest request;
  SurveyDecision decision;
  double seconds = 0.0;  // thread CPU of PlanNextStation
};

struct SurveyExplorationResult {
  int stations = 0;  // scans taken (the start included)
  PlanStatus final_status = PlanStatus::kFailed;
  std::string final_reason;
  std::vector<Pose2> visited;       // every station, the start first
  std::vector<double> decision_ms;  // thread CPU per decision
  double path_length = 0.0;         // m, driven between stations (the planned paths)
  double known_free_m2 = 0.0;       // known free and truly free
  double true_free_m2 = 0.0;
  double known_not_free_m2 = 0.0;          // known free but truly not (the map's error at walls)
  std::vector<std::string> refused_scans;  // the mapper's reasons
  double Coverage() const { return true_free_m2 > 0.0 ? known_free_m2 / true_free_m2 : 0.0; }
};

// Runs the survey from options.start; `on_step` (may be empty) sees every decision before the
// vehicle moves.
SurveyExplorationResult ExploreBySurvey(
    const std::vector<Segment>& world, const SurveyExplorationOptions& options,
    const std::function<void(const SurveyStep&, const SurveySimulation&)>& on_step = {});

}  // namespace minenav::testing
