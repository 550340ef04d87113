#include "planner/survey_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "common/angle.h"
#include "common/config.h"
#include "common/segment_index.h"
#include "planner/clearance_field.h"
#include "planner/contour_free_space.h"
#include "planner/grid_dijkstra.h"
#include "planner/occupancy_grid.h"

namespace minenav {
namespace {

// m: clearances beyond this are all "the middle of the corridor" (candidates are moved up the
// clearance until it stops growing or reaches this).
constexpr double kCentringCap = 5.0;
// Rays that decide how many arms open from an intersection candidate.
constexpr int kArmRays = 16;
// An intersection needs this many arms.
constexpr int kMinArms = 3;

// The boundary (walls, then frontiers) and its index: which hits are frontiers, and which
// of those are open (a station may close them; the others are gaps, seen through as nothing).
struct Boundary {
  explicit Boundary(const TaskMap& map)
      : num_walls(map.walls.size()), index(map.Boundary()), walls(map.walls), open(map.frontiers.size(), 1) {}
  bool IsFrontier(int i) const { return static_cast<size_t>(i) >= num_walls; }
  bool IsOpenFrontier(int i) const { return IsFrontier(i) && open[static_cast<size_t>(i) - num_walls] != 0; }
  size_t num_walls;
  StaticSegmentIndex index;
  StaticSegmentIndex walls;   // the walls alone: what blocks a line of sight
  std::vector<uint8_t> open;  // per frontier
};

PredictedView Predict(const Boundary& b, const Eigen::Vector2d& p, const SurveyPlannerOptions& o) {
  PredictedView v;
  const double dtheta = 2.0 * kPi / o.prediction_rays;
  for (int k = 0; k < o.prediction_rays; ++k) {
    const double bearing = (k + 0.5) * dtheta;
    const auto hit = b.index.CastRayDir(p, {std::cos(bearing), std::sin(bearing)}, o.sensor_range);
    if (!hit) continue;
    if (!b.IsFrontier(hit->segment)) {
      ++v.wall_rays;
      continue;
    }
    if (!b.IsOpenFrontier(hit->segment)) continue;  // a gap: nothing to see, nothing new
    ++v.frontier_rays;
    const double far = std::min(o.sensor_range, hit->range + o.unknown_depth);
    v.new_area += 0.5 * dtheta * (far * far - hit->range * hit->range);
  }
  const int seen = v.wall_rays + v.frontier_rays;
  v.overlap = seen > 0 ? static_cast<double>(v.wall_rays) / seen : 0.0;
  return v;
}

// m to the nearest wall or frontier (at most `cap`).
double Clearance(const Boundary& b, const Eigen::Vector2d& p, double cap) {
  double d = cap;
  b.index.ForEachNear(
      p, cap, [&](int i) { d = std::min(d, PointToSegmentDistance(p, b.index.segments()[static_cast<size_t>(i)])); });
  return d;
}

// Separate arms that open from p (runs of adjacent rays, round the circle, that meet a
// frontier, nothing within sensor_range, or a wall farther than twice p's clearance), and the
// bearing of the longest-looking one.
int CountArms(const Boundary& b, const Eigen::Vector2d& p, double clearance, double range, double& arm_bearing) {
  bool open[kArmRays];
  for (int k = 0; k < kArmRays; ++k) {
    const double bearing = 2.0 * kPi * k / kArmRays;
    const auto hit = b.index.CastRayDir(p, {std::cos(bearing), std::sin(bearing)}, range);
    open[k] = !hit || b.IsFrontier(hit->segment) || hit->range > 2.0 * clearance;
  }
  int arms = 0;
  arm_bearing = 0.0;
  for (int k = 0; k < kArmRays; ++k)
    if (open[k] && !open[(k + kArmRays - 1) % kArmRays]) {
      ++arms;
      if (arms == 1) arm_bearing = 2.0 * kPi * k / kArmRays;
    }
  if (arms == 0 && open[0]) arms = 1;  // open all round: one arm (a room, not an intersection)
  return arms;
}

// Lower bounds of the path length from the vehicle: Dijkstra over the cells where the
// vehicle's centre can be at all (clearance >= the footprint's inscribed radius + the
// request's, less the cells' slack), as Se2Planner's own 2-D heuristic. Infinity where no
// corridor wide enough joins the cell to the vehicle's (those need no plan); the straight
// distance when the vehicle's own cell is not among them (a tight spot: no pruning then).
class CentreDistances {
 public:
  CentreDistances(const std::vector<Segment>& boundary, double min_clearance, const Eigen::Vector2d& from, double cell)
      : frame_(GridFrame::Covering(boundary, cell, 1.0)), field_(boundary, frame_, min_clearance + 1.0), from_(from) {
    OccupancyGrid grid(frame_.nx, frame_.ny);
    for (int iy = 0; iy < frame_.ny; ++iy)
      for (int ix = 0; ix < frame_.nx; ++ix)
        grid.SetBlocked(ix, iy, field_.AtCell(ix, iy) < min_clearance - field_.Slack());
    const GridCell source{frame_.CellX(from.x()), frame_.CellY(from.y())};
    if (grid.Free(source.x, source.y)) distances_ = GridDistancesFrom(grid, source);
  }
  // m, at most the length of any path of the vehicle's centre from `from` to p.
  double LowerBound(const Eigen::Vector2d& p) const {
    const double straight = (p - from_).norm();
    if (distances_.empty()) return straight;
    const int ix = frame_.CellX(p.x()), iy = frame_.CellY(p.y());
    if (!frame_.Contains(ix, iy)) return std::numeric_limits<double>::infinity();
    const double cells = distances_[static_cast<size_t>(frame_.Index(ix, iy))];
    if (!std::isfinite(cells)) return cells;
    // 8-connected steps exceed the straight line by at most 8.2 %; the ends may lie anywhere in their cells.
    return std::max(straight, cells * frame_.cell / 1.0823922002923940 - 2.0 * field_.Slack());
  }

 private:
  GridFrame frame_;
  ClearanceField field_;
  Eigen::Vector2d from_;
  std::vector<double> distances_;
};

bool NearAny(const Eigen::Vector2d& p, const std::vector<Pose2>& poses, double distance) {
  for (const Pose2& q : poses)
    if ((q.translation() - p).norm() < distance) return true;
  return false;
}

std::string Point(const Eigen::Vector2d& p) { return "(" + FixedNumber(p.x(), 1) + ", " + FixedNumber(p.y(), 1) + ")"; }

}  // namespace

std::string ValidateOptions(const SurveyPlannerOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.sensor_range)) return "sensor_range must be > 0";
  if (o.prediction_rays < 8) return "prediction_rays must be at least 8";
  if (!std::isfinite(o.min_overlap) || o.min_overlap < 0.0 || o.min_overlap > 1.0)
    return "min_overlap must be in [0, 1]";
  if (!positive(o.unknown_depth)) return "unknown_depth must be > 0";
  if (!std::isfinite(o.area_value) || o.area_value < 0.0) return "area_value must be >= 0";
  if (!std::isfinite(o.min_new_area) || o.min_new_area < 0.0) return "min_new_area must be >= 0";
  if (!std::isfinite(o.min_frontier_length) || o.min_frontier_length < 0.0) return "min_frontier_length must be >= 0";
  if (!positive(o.min_standoff)) return "min_standoff must be > 0";
  if (!std::isfinite(o.max_standoff) || o.max_standoff < o.min_standoff) return "max_standoff must be >= min_standoff";
  if (!positive(o.standoff_step)) return "standoff_step must be > 0";
  if (!std::isfinite(o.min_wall_distance) || o.min_wall_distance < 0.0) return "min_wall_distance must be >= 0";
  if (!std::isfinite(o.station_margin) || o.station_margin < 0.0) return "station_margin must be >= 0";
  if (!std::isfinite(o.min_station_spacing) || o.min_station_spacing < 0.0) return "min_station_spacing must be >= 0";
  if (!std::isfinite(o.looked_distance) || o.looked_distance < 0.0) return "looked_distance must be >= 0";
  if (!std::isfinite(o.intersection_spacing) || o.intersection_spacing < 0.0 ||
      (o.intersection_spacing > 0.0 && o.intersection_spacing < 0.1))
    return "intersection_spacing must be 0 or at least 0.1 m";
  if (o.max_plans < 1) return "max_plans must be at least 1";
  if (o.tries_per_frontier < 1) return "tries_per_frontier must be at least 1";
  if (o.plan_expansions < 1) return "plan_expansions must be at least 1";
  return "";
}

void DeclareOptions(OptionScope s, SurveyPlannerOptions& o) {
  s.AddDouble("sensor_range", &o.sensor_range, "m", "the ladar's useful range in the prediction of a station's scan",
              0.1, 1000.0);
  s.AddInt("prediction_rays", &o.prediction_rays, "rays cast from a candidate station to predict its scan", 8, 100000);
  s.AddDouble("min_overlap", &o.min_overlap, "",
              "least fraction of a station's predicted returns that fall on walls already in the map", 0.0, 1.0);
  s.AddDouble("unknown_depth", &o.unknown_depth, "m", "space beyond a frontier counted as new area", 0.1, 1000.0);
  s.AddDouble("area_value", &o.area_value, "m/m^2", "path cost one square metre of new area is worth", 0.0, 1000.0);
  s.AddDouble("min_new_area", &o.min_new_area, "m^2", "a station must be expected to see this much new area", 0.0, 1e6);
  s.AddDouble("min_frontier_length", &o.min_frontier_length, "m", "shorter frontiers are gaps, not openings", 0.0,
              1000.0);
  s.AddDouble("min_standoff", &o.min_standoff, "m", "nearest candidate station before a frontier's middle", 0.01,
              1000.0);
  s.AddDouble("max_standoff", &o.max_standoff, "m", "farthest candidate station before a frontier's middle", 0.01,
              1000.0);
  s.AddDouble("standoff_step", &o.standoff_step, "m", "grid of the candidate stations before one frontier", 0.01,
              1000.0);
  s.AddDouble("min_wall_distance", &o.min_wall_distance, "m",
              "a candidate station keeps this far from every wall and frontier (scans see walls square on)", 0.0,
              100.0);
  s.AddDouble("station_margin", &o.station_margin, "m",
              "a station's footprint keeps the request's clearance plus this from the map (room to turn a heading bin)",
              0.0, 10.0);
  s.AddDouble("min_station_spacing", &o.min_station_spacing, "m",
              "least distance from a candidate to a visited station (and between intersections)", 0.0, 1000.0);
  s.AddDouble("looked_distance", &o.looked_distance, "m",
              "a frontier a visited station saw from this near and still open is dropped (a gap)", 0.0, 1000.0);
  s.AddDouble("intersection_spacing", &o.intersection_spacing, "m",
              "grid of the search for intersections; 0 = no intersection candidates", 0.0, 100.0);
  s.AddInt("max_plans", &o.max_plans, "path plans per decision", 1, 10000);
  s.AddInt("tries_per_frontier", &o.tries_per_frontier,
           "candidates planned per frontier (its best first; when they cannot be reached the rest are not tried)", 1,
           10000);
  s.AddInt64("plan_expansions", &o.plan_expansions, "path planner expansions each plan may take", 1, 1'000'000'000);
}

PredictedView PredictView(const TaskMap& map, const Eigen::Vector2d& position, const SurveyPlannerOptions& options) {
  if (map.walls.empty() && map.frontiers.empty()) return {};
  Boundary boundary(map);
  for (size_t i = 0; i < map.frontiers.size(); ++i)
    boundary.open[i] = map.frontiers[i].length() >= options.min_frontier_length ? 1 : 0;
  return Predict(boundary, position, options);
}

SurveyDecision PlanNextStation(const TaskMap& map_in, const Footprint& footprint_in, const SurveyRequest& r,
                               const SurveyPlannerOptions& o, const Se2PlannerOptions& planner_options,
                               const SearchLimits& limits, Se2PlannerCache* planners) {
  SurveyDecision d;
  d.path_clearance = r.clearance;
  auto finish = [&](PlanStatus status, const std::string& why) {
    d.plan.status = status;
    d.plan.reason = why;
    if (d.path_clearance < r.clearance)
      d.plan.reason += " (the vehicle stood within " + FixedNumber(r.clearance) +
                       " m of a wall: its paths keep " + FixedNumber(d.path_clearance) + " m)";
    return d;
  };
  if (const std::string e = ValidateOptions(o); !e.empty()) return finish(PlanStatus::kFailed, "bad options: " + e);
  if (const std::string e = ValidateFootprint(footprint_in); !e.empty())
    return finish(PlanStatus::kFailed, "bad footprint: " + e);
  if (!std::isfinite(r.vehicle.x) || !std::isfinite(r.vehicle.y) || !std::isfinite(r.vehicle.theta))
    return finish(PlanStatus::kFailed, "the vehicle pose is not finite");
  if (!std::isfinite(r.clearance) || r.clearance < 0.0)
    return finish(PlanStatus::kFailed, "clearance " + FixedNumber(r.clearance) + " m is not >= 0");
  if (!map_in.oriented)
    return finish(PlanStatus::kFailed, "a survey needs a contour map (its frontiers), not a line map");
  if (map_in.walls.empty()) return finish(PlanStatus::kFailed, "the map has no walls yet");
  const Footprint footprint = Normalized(footprint_in);
  // The vehicle stands where the ladar looked from: a frontier through it is no boundary.
  const TaskMap map = WithoutFrontiersAt(map_in, footprint, r.vehicle, r.clearance + planner_options.collision_step,
                                         &d.frontiers_at_vehicle);

  Boundary boundary(map);
  const KnownFreeSpace known(map.AsFreeSpace());
  Se2PlannerOptions po = planner_options;
  po.clearance = r.clearance;
  // A vehicle within the clearance of a wall (it stopped short where the map grew around it)
  // leaves with the clearance it has (as the path planner does with such a start); the reason
  // says so.
  const std::vector<Segment> walls = map.Boundary();
  std::shared_ptr<const Se2Planner> chosen = PlannerFor(planners, walls, footprint, po);
  if (chosen->setup_error().empty() && !chosen->PoseFree(r.vehicle)) {
    if (const std::optional<Se2PlannerOptions> leaving = chosen->LeavingOptions(r.vehicle)) {
      po = *leaving;
      chosen = PlannerFor(planners, walls, footprint, po);
    }
  }
  d.path_clearance = po.clearance;
  const Se2Planner& planner = *chosen;
  if (!planner.setup_error().empty()) return finish(PlanStatus::kFailed, "path planner: " + planner.setup_error());
  // Stations keep station_margin more than the paths: room to turn there, and to stay free
  // when the next scans move the walls a few centimetres.
  Se2PlannerOptions roomy_options = po;
  roomy_options.clearance = r.clearance + o.station_margin;
  roomy_options.collision_step = planner_options.collision_step;  // not a leaving step: stations are roomy
  const std::shared_ptr<const Se2Planner> roomy_planner = PlannerFor(planners, walls, footprint, roomy_options);
  const Se2Planner& roomy = *roomy_planner;
  if (!planner.PoseFree(r.vehicle))
    return finish(PlanStatus::kFailed, "the vehicle at " + PoseText(r.vehicle) +
                                           " is in collision with the map (it touches a wall)");
  std::vector<Pose2> visited = r.visited;
  visited.push_back(r.vehicle);  // it has scanned where it stands
  const CentreDistances centre(walls, InscribedRadius(footprint) + po.clearance, r.vehicle.translation(),
                               planner_options.field_resolution);

  // The frontiers worth a station: long enough, not already looked at from close by.
  for (size_t i = 0; i < map.frontiers.size(); ++i) {
    const Segment& f = map.frontiers[i];
    if (f.length() < o.min_frontier_length) {
      ++d.short_frontiers;
      boundary.open[i] = 0;
      continue;
    }
    FrontierState state{f, i, ""};
    const Eigen::Vector2d middle = 0.5 * (f.a + f.b);
    for (const Pose2& v : visited) {
      const Eigen::Vector2d to = middle - v.translation();
      const double distance = to.norm();
      if (distance > o.looked_distance || distance < 1e-9) continue;
      const auto hit = boundary.index.CastRayDir(v.translation(), to / distance, distance + 0.01);
      if (hit && static_cast<size_t>(hit->segment) == boundary.num_walls + i) {
        state.dropped = "seen from the station at " + Point(v.translation()) + " " + FixedNumber(distance, 1) +
                        " m away and still open";
        break;
      }
    }
    if (!state.dropped.empty()) boundary.open[i] = 0;
    d.frontiers.push_back(state);
  }

  // Candidates before each open frontier.
  // The headings a station may have, in order of preference: the vehicle's (no turn), its
  // opposite, along the nearest wall both ways (a corridor's axis: a long vehicle fits there),
  // facing the frontier or arm, its opposite and square to it.
  auto headings_for = [&](const Eigen::Vector2d& p, double facing) {
    std::vector<double> h = {r.vehicle.theta, r.vehicle.theta + kPi};
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector2d along = Eigen::Vector2d::Zero();
    boundary.walls.ForEachNear(p, kCentringCap, [&](int i) {
      const Segment& w = boundary.walls.segments()[static_cast<size_t>(i)];
      const double dw = PointToSegmentDistance(p, w);
      if (dw < nearest && w.length() > 0.0) nearest = dw, along = w.direction();
    });
    if (nearest < kCentringCap) {
      h.push_back(std::atan2(along.y(), along.x()));
      h.push_back(std::atan2(along.y(), along.x()) + kPi);
    }
    for (const double a : {0.0, kPi, 0.5 * kPi, -0.5 * kPi}) h.push_back(facing + a);
    return h;
  };
  std::vector<std::vector<double>> headings;  // per candidate, in order of preference
  // Candidates move to the middle of their corridor (up the clearance, 0.25 m steps, at most
  // 2 m): a long vehicle fits there, and a scan from there sees both walls square on.
  auto centred = [&](Eigen::Vector2d p) {
    double c = Clearance(boundary, p, kCentringCap);
    for (int step = 0; step < 8; ++step) {
      Eigen::Vector2d best = p;
      double best_c = c;
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector2d q = p + 0.25 * Eigen::Vector2d(std::cos(k * kPi / 4), std::sin(k * kPi / 4));
        const double cq = Clearance(boundary, q, kCentringCap);
        if (cq > best_c + 0.01) best = q, best_c = cq;
      }
      if (best == p) break;
      p = best, c = best_c;
    }
    return p;
  };
  std::vector<Eigen::Vector2d> placed;  // candidate positions so far (no two within 0.5 m)
  // A candidate from `raw`; for a frontier's (`frontier` >= 0) it must stay min_standoff to
  // max_standoff from the frontier's `middle`, with no wall in between.
  auto add_candidate = [&](const Eigen::Vector2d& raw, int frontier, const Eigen::Vector2d& middle, double facing) {
    const Eigen::Vector2d p = centred(raw);
    if (std::any_of(placed.begin(), placed.end(), [&](const Eigen::Vector2d& q) { return (q - p).norm() < 0.5; }))
      return;
    placed.push_back(p);
    StationCandidate c;
    c.pose = Pose2(p.x(), p.y(), NormalizeAngle(r.vehicle.theta));
    c.frontier = frontier;
    if (frontier >= 0) {
      c.standoff = (p - middle).norm();
      if (c.standoff < o.min_standoff - 1e-9 || c.standoff > o.max_standoff + 1e-9) return;
      if (boundary.walls.CastRayDir(p, (middle - p) / c.standoff, c.standoff)) return;  // the frontier not in sight
    }
    if (NearAny(p, visited, o.min_station_spacing)) return;  // not a candidate at all
    if (Clearance(boundary, p, o.min_wall_distance) < o.min_wall_distance || !known.Contains(p)) return;
    c.view = Predict(boundary, p, o);
    const double distance = centre.LowerBound(p);
    c.bound = distance - o.area_value * c.view.new_area;
    if (!std::isfinite(distance))
      c.rejected = "not reachable (no corridor wide enough for the footprint)";
    else if (c.view.wall_rays + c.view.frontier_rays == 0)
      c.rejected = "sees nothing within sensor_range";
    else if (c.view.overlap < o.min_overlap)
      c.rejected = "overlap " + FixedNumber(c.view.overlap) + " < " + FixedNumber(o.min_overlap);
    else if (c.view.new_area < o.min_new_area)
      c.rejected = "new area " + FixedNumber(c.view.new_area, 1) + " < " + FixedNumber(o.min_new_area, 1) + " m^2";
    std::vector<double> free;
    if (c.rejected.empty()) {
      for (const double h : headings_for(p, facing)) {
        const double heading = NormalizeAngle(h);
        const bool seen = std::any_of(free.begin(), free.end(),
                                      [&](double g) { return std::abs(NormalizeAngle(g - heading)) < 1e-6; });
        if (!seen && roomy.PoseFree(Pose2(p.x(), p.y(), heading))) free.push_back(heading);
      }
      if (free.empty())
        c.rejected = "the footprint (with station_margin) fits there at no heading tried";
      else
        c.pose.theta = free.front(), c.feasible = true;
    }
    d.candidates.push_back(c);
    headings.push_back(free);
  };
  for (size_t i = 0; i < d.frontiers.size(); ++i) {
    if (!d.frontiers[i].dropped.empty()) continue;
    const Segment& f = d.frontiers[i].segment;
    const Eigen::Vector2d middle = 0.5 * (f.a + f.b), along = f.direction().normalized();
    const Eigen::Vector2d inward(-along.y(), along.x());  // the free side
    const int n = static_cast<int>(std::floor(o.max_standoff / o.standoff_step));
    for (int ix = -n; ix <= n; ++ix)
      for (int iy = -n; iy <= n; ++iy) {
        const Eigen::Vector2d offset = o.standoff_step * Eigen::Vector2d(ix, iy);
        const double standoff = offset.norm();
        if (standoff < o.min_standoff - 1e-9 || standoff > o.max_standoff + 1e-9 || offset.dot(inward) <= 0.0) continue;
        // The frontier's middle in sight: no wall before it on the way there.
        const Eigen::Vector2d p = middle + offset;
        if (boundary.walls.CastRayDir(p, -offset / standoff, standoff)) continue;
        add_candidate(p, static_cast<int>(i), middle, std::atan2(-offset.y(), -offset.x()));
      }
  }

  // Intersections: points where at least three arms open, the most open of each cluster.
  if (o.intersection_spacing > 0.0) {
    Eigen::Vector2d lo = map.walls.front().a, hi = lo;
    for (const Segment& s : map.walls) {
      lo = lo.cwiseMin(s.a).cwiseMin(s.b);
      hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    }
    const double min_clearance = InscribedRadius(footprint) + r.clearance;
    struct Crossing {
      Eigen::Vector2d p;
      double clearance, arm_bearing;
    };
    std::vector<Crossing> crossings;
    for (double x = lo.x() + 0.5 * o.intersection_spacing; x < hi.x(); x += o.intersection_spacing)
      for (double y = lo.y() + 0.5 * o.intersection_spacing; y < hi.y(); y += o.intersection_spacing) {
        const Eigen::Vector2d p(x, y);
        const double c = Clearance(boundary, p, o.sensor_range);
        if (c < min_clearance || !known.Contains(p)) continue;
        double arm_bearing = 0.0;
        if (CountArms(boundary, p, c, o.sensor_range, arm_bearing) >= kMinArms)
          crossings.push_back({p, c, arm_bearing});
      }
    std::sort(crossings.begin(), crossings.end(),
              [](const Crossing& a, const Crossing& b) { return a.clearance > b.clearance; });
    std::vector<Pose2> picked;
    for (const Crossing& c : crossings) {
      if (NearAny(c.p, picked, std::max(o.min_station_spacing, 2.0 * o.intersection_spacing))) continue;
      picked.emplace_back(c.p.x(), c.p.y(), 0.0);
      add_candidate(c.p, -1, c.p, c.arm_bearing);
    }
  }

  // Plan in order of the lower bound of the cost until no bound can beat the best found.
  std::vector<size_t> order;
  for (size_t k = 0; k < d.candidates.size(); ++k)
    if (d.candidates[k].rejected.empty()) order.push_back(k);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return d.candidates[a].bound < d.candidates[b].bound; });
  SearchLimits plan_limits = limits;
  plan_limits.max_expansions = std::min(limits.max_expansions, o.plan_expansions);
  int untried = 0, calls = 0;
  bool stopped = false;
  std::map<int, int> tried_at;  // candidates planned per frontier (-1: the intersections)
  for (const size_t k : order) {
    StationCandidate& c = d.candidates[k];
    if (d.chosen && c.bound >= d.candidates[*d.chosen].cost) {
      c.rejected = "cannot beat the chosen station";
      continue;
    }
    if (tried_at[c.frontier] >= o.tries_per_frontier) {
      c.rejected = "not planned (tries_per_frontier)";
      continue;
    }
    if (d.plans >= o.max_plans || calls >= 10 * o.max_plans || stopped) {
      c.rejected = "not planned (max_plans)";
      ++untried;
      continue;
    }
    c.planned = true;
    ++tried_at[c.frontier];
    std::string why;
    bool reached = false;
    for (const double h : headings[k]) {
      if (d.plans >= o.max_plans) break;
      const Pose2 goal(c.pose.x, c.pose.y, h);
      const Se2PlanResult p = planner.Plan(r.vehicle, goal, plan_limits);
      ++calls;
      // A plan answered before searching (no corridor wide enough joins the two: no heading
      // reaches there) is cheap and does not count towards max_plans.
      if (p.expansions > 0) ++d.plans;
      d.expansions += p.expansions;
      c.expansions += p.expansions;
      if (p.status == SearchStatus::kFound) {
        reached = true;
        c.pose = goal;
        c.path_cost = p.cost;
        c.cost = p.cost - o.area_value * c.view.new_area;
        if (!d.chosen || c.cost < d.candidates[*d.chosen].cost) {
          d.chosen = k;
          d.path = p.path;
        }
        break;
      }
      if (p.status == SearchStatus::kStopped) stopped = true;
      why = ToString(p.status);
      if (p.status == SearchStatus::kInvalidRequest) why += ": " + p.reason;
      if (stopped || p.expansions == 0) break;
    }
    if (!reached) c.rejected = "not reachable (" + (why.empty() ? std::string("no plan") : why) + ")";
  }

  if (d.chosen) {
    const StationCandidate& c = d.candidates[*d.chosen];
    Task t;
    t.id = 1;
    t.kind = TaskKind::kScanStation;
    t.target = c.pose;
    t.clearance = r.clearance;
    t.allow_reverse = true;
    t.appendages = Appendages::kStowed;
    const std::string what =
        c.frontier >= 0 ? FixedNumber(c.standoff, 1) + " m before frontier " + std::to_string(c.frontier) + " (" +
                              FixedNumber(d.frontiers[static_cast<size_t>(c.frontier)].segment.length(), 1) + " m)"
                        : "at an intersection";
    std::ostringstream line;
    line << "scan station " << PoseText(c.pose) << " " << what << ": overlap " << FixedNumber(c.view.overlap) << ", "
         << FixedNumber(c.view.new_area, 0) << " m^2 new, path " << FixedNumber(d.path.Length(), 1) << " m";
    t.description = line.str();
    d.plan.tasks.push_back(t);
    int open = 0;
    for (const FrontierState& f : d.frontiers) open += f.dropped.empty() ? 1 : 0;
    return finish(PlanStatus::kOk, t.description + "; " + std::to_string(d.candidates.size()) + " candidates at " +
                                       std::to_string(open) + " open frontiers, " + std::to_string(d.plans) + " plans");
  }

  // No station: say why, frontier by frontier.
  if (untried > 0 || stopped)
    return finish(PlanStatus::kFailed, "no station found within the plan budget: " + std::to_string(d.plans) +
                                           " plans, none reachable; " + std::to_string(untried) +
                                           " candidates not tried" + (stopped ? " (stopped at the deadline)" : ""));
  if (d.frontiers.empty())
    return finish(PlanStatus::kComplete, "no frontier left: the known free space is closed (" +
                                             std::to_string(d.short_frontiers) + " gaps shorter than " +
                                             FixedNumber(o.min_frontier_length) + " m ignored)");
  std::ostringstream why;
  why << "no reachable frontier: " << d.frontiers.size() << " frontier" << (d.frontiers.size() > 1 ? "s" : "")
      << " left, none reachable:";
  for (size_t i = 0; i < d.frontiers.size(); ++i) {
    const FrontierState& f = d.frontiers[i];
    why << (i == 0 ? " " : "; ") << "frontier " << i << " (" << FixedNumber(f.segment.length(), 1) << " m at "
        << Point(0.5 * (f.segment.a + f.segment.b)) << ") ";
    if (!f.dropped.empty()) {
      why << f.dropped;
      continue;
    }
    std::map<std::string, int> reasons;
    int count = 0;
    for (const StationCandidate& c : d.candidates)
      if (c.frontier == static_cast<int>(i)) ++reasons[c.rejected], ++count;
    if (count == 0) {
      why << "no candidate station in the known free space in sight of it";
      continue;
    }
    why << count << " candidates: ";
    bool first = true;
    for (const auto& [reason, n] : reasons) {
      why << (first ? "" : ", ") << n << " " << reason;
      first = false;
    }
  }
  int crossings = 0;
  for (const StationCandidate& c : d.candidates) crossings += c.frontier < 0 ? 1 : 0;
  if (crossings > 0) why << "; " << crossings << " intersection candidates, none a station";
  return finish(PlanStatus::kComplete, why.str());
}

}  // namespace minenav
