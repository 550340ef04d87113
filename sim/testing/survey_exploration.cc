#include "sim/testing/survey_exploration.h"

#include <algorithm>

#include "common/angle.h"

#include "common/node/cpu_time.h"
#include "common/scan.h"
#include "planner/contour_free_space.h"
#include "sensor_driver/ladar_model.h"

namespace minenav::testing {
namespace {

constexpr int64_t kT0 = 1'000'000'000'000'000;

LadarModel Model(double range, int points) {
  LadarModel m = LadarModel::Typhoon();
  m.max_range = range;
  m.num_points = points;
  m.angular_resolution = 2.0 * kPi / points;
  return m;
}

}  // namespace

SurveySimulation::SurveySimulation(std::vector<Segment> world, double sensor_range, int scan_points, uint64_t seed)
    : world_(world), truth_(world), index_(std::move(world)), simulator_(Model(sensor_range, scan_points), seed) {}

std::string SurveySimulation::ScanAt(const Pose2& pose) {
  const LadarScan scan = simulator_.Simulate(index_, pose, Pose2(), kT0 + scans_ * 1'000'000, scans_);
  ++scans_;
  const mapper::InsertResult r = mapper_.InsertScan(scan, pose);
  return r.accepted ? "" : r.reason;
}

TaskMap SurveySimulation::Map() const {
  std::vector<mapper::Contour> contours;
  for (const auto& [id, c] : mapper_.map().contours()) contours.push_back(c);
  return TaskMapFromContours(contours);
}

double SurveySimulation::TrueOverlap(const TaskMap& map, const Pose2& pose) const {
  const LadarScan scan = simulator_.Simulate(index_, pose, Pose2(), kT0, 999'999);
  if (map.walls.empty()) return 0.0;
  const StaticSegmentIndex walls(map.walls);
  int valid = 0, on_map = 0;
  for (const Eigen::Vector2d& p : ScanPointsInWorld(scan, pose)) {
    ++valid;
    bool near = false;
    walls.ForEachNear(
        p, 0.3, [&](int i) { near = near || PointToSegmentDistance(p, map.walls[static_cast<size_t>(i)]) < 0.3; });
    on_map += near ? 1 : 0;
  }
  return valid > 0 ? static_cast<double>(on_map) / valid : 0.0;
}

SurveyExplorationResult ExploreBySurvey(
    const std::vector<Segment>& world, const SurveyExplorationOptions& o,
    const std::function<void(const SurveyStep&, const SurveySimulation&)>& on_step) {
  SurveySimulation sim(world, o.sensor_range, o.scan_points);
  SurveyExplorationResult result;
  SurveyRequest request;
  request.vehicle = o.start;
  request.clearance = o.clearance;
  auto scan = [&](const Pose2& pose) {
    if (const std::string why = sim.ScanAt(pose); !why.empty()) result.refused_scans.push_back(why);
    result.visited.push_back(pose);
    ++result.stations;
  };
  scan(o.start);
  for (int index = 1; result.stations < o.max_stations; ++index) {
    SurveyStep step;
    step.index = index;
    step.map = sim.Map();
    step.request = request;
    const double t0 = ThreadCpuSeconds();
    step.decision = PlanNextStation(step.map, o.footprint, request, o.survey, o.planner);
    step.seconds = ThreadCpuSeconds() - t0;
    result.decision_ms.push_back(1e3 * step.seconds);
    result.final_status = step.decision.plan.status;
    result.final_reason = step.decision.plan.reason;
    if (on_step) on_step(step, sim);
    if (step.decision.plan.status != PlanStatus::kOk) break;
    result.path_length += step.decision.path.Length();
    request.visited.push_back(request.vehicle);
    request.vehicle = step.decision.plan.tasks.front().target;
    scan(request.vehicle);
  }

  // Explored: the known free space against the true free space.
  const TaskMap map = sim.Map();
  const KnownFreeSpace known(map.AsFreeSpace());
  Eigen::Vector2d lo = world.front().a, hi = lo;
  for (const Segment& s : world) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  const double cell = o.coverage_cell, area = cell * cell;
  for (double x = lo.x() + 0.5 * cell; x < hi.x(); x += cell)
    for (double y = lo.y() + 0.5 * cell; y < hi.y(); y += cell) {
      const Eigen::Vector2d p(x, y);
      const bool free = sim.world().SameSpace(p, o.inside);
      const bool k = known.Contains(p);
      result.true_free_m2 += free ? area : 0.0;
      result.known_free_m2 += (k && free) ? area : 0.0;
      result.known_not_free_m2 += (k && !free) ? area : 0.0;
    }
  return result;
}

}  // namespace minenav::testing
