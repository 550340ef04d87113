#include "planner/se2_planner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "common/config.h"
#include "planner/analytic_shot.h"
#include "planner/corridor_route.h"
#include "planner/grid_dijkstra.h"
#include "planner/state_table.h"

namespace minenav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string PoseText(const Pose2& p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x << ", " << p.y << ", " << p.theta << ")";
  return s.str();
}

bool Finite(const Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

// A stored state, 40 bytes: its heading is the bin's (theta = start theta + heading * bin,
// the start's own for the start), its step the primitive's index.
struct Node {
  double x = 0.0, y = 0.0;
  double g = 0.0;
  int32_t parent = -1;
  float spare = 0.0f;      // m every point of the polygon may move from here and stay free (rounded down)
  int16_t heading = 0;     // heading bin
  int8_t primitive = -1;   // the step that reached it (-1: the start)
  int8_t direction = 0;    // last drive direction on the way here (+1, -1, 0 none yet)
  bool closed = false;
};
static_assert(sizeof(Node) <= 40);

// A spare distance as a float no larger than it (it must stay a guarantee).
float SpareDown(double spare) {
  float f = static_cast<float>(spare);
  if (static_cast<double>(f) > spare) f = std::nextafter(f, 0.0f);
  return f;
}

// Does a sweep collide? Poses 1..n, `spacing` m apart for the farthest point of the polygon;
// check(i) checks pose i. A pose free with s m to spare covers every pose within s + step / 2
// of it (the margin holds half a collision step), so the next checked pose may lie s + step
// beyond it: where the field says the polygon is far from the walls most poses are skipped.
// `spare0` is the spare of the start pose (0 when unknown). `spare_end` gets the end pose's.
template <typename Check>
bool SweepCollides(int n, double spacing, double step, double spare0, Check check, double* spare_end) {
  double spare = spare0, reached = 0.0;
  int i = 0;
  while (i < n) {
    const double limit = reached + spare + step;
    const int j = std::min(n, std::max(i + 1, static_cast<int>(std::floor(limit / spacing + 1e-9))));
    const PoseCheck c = check(j);
    if (c.collides) return true;
    spare = c.spare;
    reached = j * spacing;
    i = j;
  }
  if (spare_end) *spare_end = spare;
  return false;
}

// m the farthest point of the polygon (within rc of the pose) moves along the piece.
double Sweep(const MotionPiece& piece, double rc) {
  if (piece.motion == Motion::kTurnInPlace) return rc * std::abs(piece.amount);
  if (IsArc(piece.motion)) return piece.amount * (piece.radius + rc) / piece.radius;
  return piece.amount;
}

// The lower bound on the cost from p to the goal without obstacles (admissible): at least the
// distance d driven (at min(1, reverse_factor) per metre) and the heading difference turned,
// by arcs (1 / R rad per metre, which also covers distance) or in place; the cheapest mix
// drives d on arcs and turns the rest in place or on further arcs, whichever costs less.
double FreeSpaceLowerBound(const Pose2& p, const Pose2& goal, double r, const MotionCosts& costs) {
  const double k = std::min(1.0, costs.reverse_factor);
  const double d = std::hypot(goal.x - p.x, goal.y - p.y);
  const double turn = std::abs(NormalizeAngle(goal.theta - p.theta));
  return k * d + std::min(k * r, costs.turn_in_place_per_rad) * std::max(0.0, turn - d / r);
}

// The largest ratio of the 8-connected grid distance to the straight-line distance
// (1 / cos 22.5 deg): the 2-D distances divided by it do not overestimate.
constexpr double kOctileStretch = 1.0823922002923940;

constexpr int kPrimitives = 8;
// The motions of one step: each straight move and arc as long as the arc that turns one bin.
std::array<MotionPiece, kPrimitives> Primitives(double r, double bin) {
  const double step = r * bin;
  return {{{Motion::kForward, step, 0.0, {}},
           {Motion::kReverse, step, 0.0, {}},
           {Motion::kArcLeft, step, r, {}},
           {Motion::kArcRight, step, r, {}},
           {Motion::kArcLeftReverse, step, r, {}},
           {Motion::kArcRightReverse, step, r, {}},
           {Motion::kTurnInPlace, bin, 0.0, {}},
           {Motion::kTurnInPlace, -bin, 0.0, {}}}};
}
// m any point of the polygon moves between the poses of an analytic shot looked at before
// it is swept (Search: a blocked shot is mostly found there, at a few checks).
constexpr double kCoarseShotSpacing = 3.0;
// Heading bins each primitive turns.
constexpr int kHeadingChange[kPrimitives] = {0, 0, 1, -1, -1, 1, 1, -1};

// The open list's order: least f first; among equal f (within 1e-9) the deeper node, larger
// g (Nav2 Smac's tie-break: along a corridor f is nearly constant, and without it the search
// widens over the whole plateau instead of following it).
struct OpenEntry {
  double f, g;
  int32_t node;
  bool operator<(const OpenEntry& o) const { return f > o.f + 1e-9 || (f > o.f - 1e-9 && g < o.g); }
};

}  // namespace

std::string ValidateOptions(const Se2PlannerOptions& o) {
  if (!(o.turn_radius > 0.0)) return "turn_radius must be > 0";
  if (!(o.clearance >= 0.0)) return "clearance must be >= 0";
  if (o.heading_bins < 8 || o.heading_bins > 720) return "heading_bins must be in [8, 720]";
  if (!(o.xy_resolution > 0.0) || !(o.field_resolution > 0.0)) return "xy_resolution and field_resolution must be > 0";
  const double step = o.turn_radius * 2.0 * kPi / o.heading_bins;
  if (step <= std::sqrt(2.0) * o.xy_resolution)
    return "the step (turn_radius * 2 pi / heading_bins = " + std::to_string(step) +
           " m) must leave its xy cell: make xy_resolution smaller than step / sqrt(2)";
  if (!(o.collision_step > 0.0)) return "collision_step must be > 0";
  if (o.analytic_shot_interval < 1) return "analytic_shot_interval must be >= 1";
  if (!(o.analytic_shot_max_cost_ratio >= 1.0)) return "analytic_shot_max_cost_ratio must be >= 1";
  if (o.collision_discs < 1 || o.collision_discs > 64) return "collision_discs must be in [1, 64]";
  if (o.cached_goals < 1 || o.cached_goals > 64) return "cached_goals must be in [1, 64]";
  if (o.corridor_leg_expansions < 1) return "corridor_leg_expansions must be >= 1";
  if (o.corridor_turn_expansions < 1) return "corridor_turn_expansions must be >= 1";
  if (!(o.corridor_route_min_distance >= 0.0)) return "corridor_route_min_distance must be >= 0";
  if (!(o.corridor_route_resolution > 0.0) || !std::isfinite(o.corridor_route_resolution))
    return "corridor_route_resolution must be finite and > 0";
  if (!(o.corridor_route_turn_cost >= 0.0) || !std::isfinite(o.corridor_route_turn_cost))
    return "corridor_route_turn_cost must be finite and >= 0";
  if (!(o.corridor_route_lead > 0.0) || !std::isfinite(o.corridor_route_lead))
    return "corridor_route_lead must be finite and > 0";
  if (!(o.heuristic_turn_cost >= 0.0) || !std::isfinite(o.heuristic_turn_cost))
    return "heuristic_turn_cost must be finite and >= 0";
  return "";
}

void DeclareOptions(OptionScope scope, Se2PlannerOptions& o) {
  scope.AddDouble("turn_radius", &o.turn_radius, "m", "the one turning radius besides turning in place", 0.01, 1000.0);
  scope.AddDouble("clearance", &o.clearance, "m", "least distance from the vehicle's polygon to any wall", 0.0, 100.0);
  scope.AddInt("heading_bins", &o.heading_bins, "heading cells per turn", 8, 720);
  scope.AddDouble("xy_resolution", &o.xy_resolution, "m", "side of the (x, y) cells of the visited states", 0.001, 10.0);
  scope.AddDouble("field_resolution", &o.field_resolution, "m", "cells of the clearance field and 2-D heuristic", 0.01,
                  10.0);
  scope.AddDouble("collision_step", &o.collision_step, "m", "most any point of the polygon moves between checked poses",
                  0.001, 1.0);
  scope.AddInt("collision_discs", &o.collision_discs, "discs of the polygon's cover for the field's quick decisions",
               1, 64);
  scope.AddBool("shot_heuristic", &o.shot_heuristic,
                "add the cheapest obstacle-free analytic shot to the heuristic (faster, may overestimate)");
  scope.AddInt("cached_goals", &o.cached_goals, "goals whose 2-D obstacle heuristic is kept between requests", 1, 64);
  scope.AddInt("analytic_shot_interval", &o.analytic_shot_interval, "expansions between analytic shots", 1, 1000000);
  scope.AddDouble("analytic_shot_max_length", &o.analytic_shot_max_length, "m", "longer analytic shots are not tried",
                  0.0, 1e6);
  scope.AddDouble("analytic_shot_max_cost_ratio", &o.analytic_shot_max_cost_ratio, "",
                  "shots dearer than this times the cheapest are not tried", 1.0, 1e6);
  scope.AddDouble("heuristic_turn_cost", &o.heuristic_turn_cost, "m",
                  "the 2-D heuristic's cost per 45 degrees of turning (0 = off; > 0 not admissible)", 0.0, 1000.0);
  scope.AddBool("corridor_waypoints", &o.corridor_waypoints,
                "with heuristic_turn_cost: plan leg by leg through the middle of the 2-D path's straight runs");
  scope.AddInt("corridor_leg_expansions", &o.corridor_leg_expansions, "expansions a corridor leg may take", 1,
               100000000);
  scope.AddBool("corridor_route", &o.corridor_route,
                "first plan along the 2-D route: shots on its straight legs, a local search round each turn");
  scope.AddDouble("corridor_route_turn_cost", &o.corridor_route_turn_cost, "m",
                  "the corridor route's cost per 45 degrees of turning", 0.0, 1000.0);
  scope.AddDouble("corridor_route_lead", &o.corridor_route_lead, "m",
                  "route before and after a turn to its local search's start and goal", 0.01, 1000.0);
  scope.AddDouble("corridor_route_min_distance", &o.corridor_route_min_distance, "m",
                  "requests with the goal nearer the start than this are not routed", 0.0, 1e6);
  scope.AddDouble("corridor_route_resolution", &o.corridor_route_resolution, "m", "cells of the corridor route's grid",
                  0.01, 100.0);
  scope.AddInt("corridor_turn_expansions", &o.corridor_turn_expansions, "expansions a leg of the corridor route may take",
               1, 100000000);
  DeclareOptions(scope.Nested("costs"), o.costs);
}

Se2Planner::Se2Planner(std::vector<Segment> map, Footprint footprint, Se2PlannerOptions options)
    : map_(std::move(map)), footprint_(std::move(footprint)), options_(options) {
  setup_error_ = ValidateOptions(options_);
  if (setup_error_.empty()) setup_error_ = ValidateFootprint(footprint_);
  if (!setup_error_.empty()) return;
  footprint_ = Normalized(footprint_);
  std::vector<Segment> walls;
  map_min_ = Eigen::Vector2d::Constant(kInf);
  map_max_ = Eigen::Vector2d::Constant(-kInf);
  for (const Segment& s : map_) {
    if (!s.a.allFinite() || !s.b.allFinite()) continue;
    walls.push_back(s);
    map_min_ = map_min_.cwiseMin(s.a).cwiseMin(s.b);
    map_max_ = map_max_.cwiseMax(s.a).cwiseMax(s.b);
  }
  if (walls.empty()) {
    setup_error_ = "the map has no segments: no free space is known";
    return;
  }
  // The map ends at the box of its segments.
  const Eigen::Vector2d lo = map_min_, hi = map_max_;
  walls.push_back({lo.x(), lo.y(), hi.x(), lo.y()});
  walls.push_back({hi.x(), lo.y(), hi.x(), hi.y()});
  walls.push_back({hi.x(), hi.y(), lo.x(), hi.y()});
  walls.push_back({lo.x(), hi.y(), lo.x(), lo.y()});
  // A map of absurd extent for the field's cells (hostile coordinates) is refused here, well
  // below GridFrame::kMaxDenseCells: the grids of the same extent that its users build (the
  // survey planner's, a metre wider) then stay within it too.
  const Eigen::Vector2d cells = (hi - lo) / options_.field_resolution + Eigen::Vector2d::Constant(2.0);
  if (!(cells.x() * cells.y() <= kMaxFieldCells)) {
    std::ostringstream why;
    why << "the map spans " << hi.x() - lo.x() << " x " << hi.y() - lo.y() << " m: more than " << kMaxFieldCells
        << " cells of field_resolution " << options_.field_resolution << " m";
    setup_error_ = why.str();
    return;
  }
  walls_ = std::make_unique<StaticSegmentIndex>(walls);
  const double margin = options_.clearance + 0.5 * options_.collision_step;
  const GridFrame frame = GridFrame::Covering(lo, hi, options_.field_resolution, 0.0);
  const double slack = 0.5 * std::sqrt(2.0) * options_.field_resolution;
  field_ = std::make_unique<ClearanceField>(walls, frame, CircumscribedRadius(footprint_) + margin + 3.0 * slack);
  checker_ = std::make_unique<FootprintCollisionChecker>(*walls_, *field_, footprint_, margin, options_.collision_discs);
  centre_cells_ = OccupancyGrid(frame.nx, frame.ny);
  for (int iy = 0; iy < frame.ny; ++iy)
    for (int ix = 0; ix < frame.nx; ++ix) {
      const double c = field_->AtCell(ix, iy);
      largest_clearance_ = std::max(largest_clearance_, c);
      centre_cells_.SetBlocked(ix, iy, c + slack < checker_->inscribed_radius() + margin);
    }
  roomy_cells_.assign(centre_cells_.blocked.size(), 0);
  const double roomy = 0.5 * (checker_->inscribed_radius() + checker_->circumscribed_radius()) + margin;
  for (int iy = 0; iy < frame.ny; ++iy)
    for (int ix = 0; ix < frame.nx; ++ix)
      roomy_cells_[centre_cells_.Index(ix, iy)] = field_->AtCell(ix, iy) + slack >= roomy ? 1 : 0;
  if (options_.corridor_route)
    route_grid_ = CoarseRouteGrid(frame, centre_cells_, roomy_cells_,
                                  std::max(options_.corridor_route_resolution, frame.cell));
}

bool Se2Planner::PoseFree(const Pose2& pose) const { return checker_ && !checker_->Collides(pose); }

std::optional<Se2PlannerOptions> Se2Planner::LeavingOptions(const Pose2& pose) const {
  if (!checker_) return std::nullopt;
  if (PoseFree(pose)) return options_;
  // Within the margin: the spare is 0 and the exact distance is measured with no margin.
  const FootprintCollisionChecker bare(*walls_, *field_, footprint_, 0.0, options_.collision_discs);
  const double distance = bare.ExactSpare(pose, std::cos(pose.theta), std::sin(pose.theta));
  constexpr double kRounding = 0.005;  // m: clearances in steps of 5 mm, one step below what it has
  constexpr double kSpare = 0.001;     // m the pose keeps beyond the margin of the relaxed planner
  Se2PlannerOptions leaving = options_;
  const double room = distance - 0.5 * options_.collision_step;
  leaving.clearance = std::max(0.0, std::floor(room / kRounding) * kRounding - kRounding);
  if (room - leaving.clearance >= kSpare) return leaving;
  // Within the half-step (the clearance is 0 here): the polygon swept between checked poses
  // keeps clear of the walls with a finer step (in whole millimetres, below the half-step).
  leaving.collision_step = std::floor(2.0 * (distance - kSpare) / 0.001) * 0.001;
  if (!(leaving.collision_step >= kLeastCollisionStep)) return std::nullopt;
  return leaving;
}

bool Se2Planner::PieceCollides(const Pose2& from, const MotionPiece& piece) const {
  const double sweep = Sweep(piece, checker_->circumscribed_radius());
  const int n = std::max(1, static_cast<int>(std::ceil(sweep / options_.collision_step)));
  const PoseCheck at_start = checker_->Check(from);
  const PieceSampler along(from, piece.motion, piece.radius);
  return SweepCollides(
      n, sweep / n, options_.collision_step, at_start.collides ? 0.0 : at_start.spare,
      [&](int i) {
        const PieceSampler::Sample q = along.At(piece.amount * static_cast<double>(i) / n);
        return checker_->Check(q.pose, q.cos_theta, q.sin_theta);
      },
      nullptr);
}

const std::vector<Se2Planner::SweptPrimitive>& Se2Planner::PrimitivesFor(double phase) const {
  if (phase == primitives_phase_) return primitives_;
  const int bins = options_.heading_bins;
  const double bin = 2.0 * kPi / bins, rc = checker_->circumscribed_radius();
  const auto primitives = Primitives(options_.turn_radius, bin);
  primitives_.assign(static_cast<size_t>(bins * kPrimitives), {});
  for (int k = 0; k < bins; ++k) {
    const Pose2 from(0.0, 0.0, NormalizeAngle(phase + k * bin));
    for (int m = 0; m < kPrimitives; ++m) {
      const MotionPiece& piece = primitives[static_cast<size_t>(m)];
      SweptPrimitive& swept = primitives_[static_cast<size_t>(k * kPrimitives + m)];
      const double sweep = Sweep(piece, rc);
      const int n = std::max(1, static_cast<int>(std::ceil(sweep / options_.collision_step)));
      swept.spacing = sweep / n;
      swept.end_heading = ((k + kHeadingChange[m]) % bins + bins) % bins;
      for (int i = 1; i <= n; ++i) {
        Pose2 p = PoseAfter(from, piece.motion, piece.amount * static_cast<double>(i) / n, piece.radius);
        if (i == n) p.theta = NormalizeAngle(phase + swept.end_heading * bin);
        swept.poses.push_back({p.x, p.y, p.theta, std::cos(p.theta), std::sin(p.theta)});
      }
    }
  }
  primitives_phase_ = phase;
  return primitives_;
}

LazyGridDistances& Se2Planner::DistancesTo(GridCell goal) const {
  for (auto it = goal_distances_.begin(); it != goal_distances_.end(); ++it)
    if ((*it)->source() == goal) {
      if (it != goal_distances_.begin()) {
        auto hit = std::move(*it);
        goal_distances_.erase(it);
        goal_distances_.push_front(std::move(hit));
      }
      return *goal_distances_.front();
    }
  goal_distances_.push_front(std::make_unique<LazyGridDistances>(centre_cells_, goal));
  while (goal_distances_.size() > static_cast<size_t>(options_.cached_goals)) goal_distances_.pop_back();
  return *goal_distances_.front();
}

LazyHeadingGridDistances& Se2Planner::HeadingDistancesTo(GridCell goal, int heading, double turn_cost) const {
  const double cell_turn_cost = turn_cost / field_->frame().cell;
  for (auto it = goal_heading_distances_.begin(); it != goal_heading_distances_.end(); ++it)
    if ((*it)->source() == goal && (*it)->source_heading() == heading && (*it)->turn_cost() == cell_turn_cost) {
      if (it != goal_heading_distances_.begin()) {
        auto hit = std::move(*it);
        goal_heading_distances_.erase(it);
        goal_heading_distances_.push_front(std::move(hit));
      }
      return *goal_heading_distances_.front();
    }
  goal_heading_distances_.push_front(std::make_unique<LazyHeadingGridDistances>(
      centre_cells_, goal, heading, cell_turn_cost,
      std::max(1.0, options_.costs.reverse_factor), &roomy_cells_, 4.0));
  while (goal_heading_distances_.size() > static_cast<size_t>(options_.cached_goals))
    goal_heading_distances_.pop_back();
  return *goal_heading_distances_.front();
}

std::string Se2Planner::CheckPose(const Pose2& pose, const std::string& what) const {
  if (!Finite(pose)) return what + " " + PoseText(pose) + " is not finite";
  if (pose.x < map_min_.x() || pose.y < map_min_.y() || pose.x > map_max_.x() || pose.y > map_max_.y()) {
    std::ostringstream s;
    s << what << " " << PoseText(pose) << " is outside the map (its segments span [" << map_min_.x() << ", "
      << map_max_.x() << "] x [" << map_min_.y() << ", " << map_max_.y() << "] m)";
    return s.str();
  }
  if (checker_->Collides(pose))
    return what + " " + PoseText(pose) + " is in collision: the footprint is within " +
           std::to_string(options_.clearance) + " m of a wall";
  return "";
}

GridCell Se2Planner::CentredCell(GridCell c, int heading) const {
  // Across the heading (for x or y only): the cell of most clearance within 5 m.
  if (heading % 2 == 1) return c;
  const int px = heading % 4 == 0 ? 0 : 1, py = 1 - px;
  const int reach = static_cast<int>(5.0 / field_->frame().cell);
  GridCell best = c;
  double best_clearance = field_->AtCell(c.x, c.y);
  for (const int sign : {1, -1})
    for (int j = 1; j <= reach; ++j) {
      const int cx = c.x + sign * j * px, cy = c.y + sign * j * py;
      if (!centre_cells_.Free(cx, cy)) break;
      if (field_->AtCell(cx, cy) > best_clearance) best_clearance = field_->AtCell(cx, cy), best = {cx, cy};
    }
  return best;
}

Pose2 Se2Planner::CentredPose(GridCell c, int heading) const {
  const GridFrame& frame = field_->frame();
  const GridCell best = CentredCell(c, heading);
  const Eigen::Vector2d centre = frame.CellMin(best.x, best.y) + Eigen::Vector2d::Constant(0.5 * frame.cell);
  return Pose2(centre.x(), centre.y(), NormalizeAngle(heading * kPi / 4.0));
}

std::vector<RouteStep> Se2Planner::Route(const Pose2& start, const Pose2& goal, double turn_cost, bool coarse) const {
  if (!Finite(start) || !Finite(goal)) return {};
  const GridFrame& fine = field_->frame();
  if (!coarse) {
    LazyHeadingGridDistances& d = HeadingDistancesTo({fine.CellX(goal.x), fine.CellY(goal.y)},
                                                     LazyHeadingGridDistances::HeadingOf(goal.theta), turn_cost);
    return DescendRoute(d, centre_cells_, {fine.CellX(start.x), fine.CellY(start.y)},
                        LazyHeadingGridDistances::HeadingOf(start.theta));
  }
  const GridFrame& frame = route_grid_.frame;
  const GridCell goal_cell{frame.CellX(goal.x), frame.CellY(goal.y)};
  const int goal_heading = LazyHeadingGridDistances::HeadingOf(goal.theta);
  const double cell_turn_cost = turn_cost / frame.cell;
  LazyHeadingGridDistances* d = nullptr;
  for (auto it = route_distances_.begin(); it != route_distances_.end() && !d; ++it)
    if ((*it)->source() == goal_cell && (*it)->source_heading() == goal_heading && (*it)->turn_cost() == cell_turn_cost)
      d = it->get();
  if (!d) {
    route_distances_.push_front(std::make_unique<LazyHeadingGridDistances>(
        route_grid_.cells, goal_cell, goal_heading, cell_turn_cost, std::max(1.0, options_.costs.reverse_factor),
        &route_grid_.roomy, 4.0));
    while (route_distances_.size() > static_cast<size_t>(options_.cached_goals)) route_distances_.pop_back();
    d = route_distances_.front().get();
  }
  std::vector<RouteStep> route = DescendRoute(*d, route_grid_.cells, {frame.CellX(start.x), frame.CellY(start.y)},
                                              LazyHeadingGridDistances::HeadingOf(start.theta));
  for (RouteStep& step : route)  // to the field's cells
    step.cell = {fine.CellX(frame.x0 + (step.cell.x + 0.5) * frame.cell),
                 fine.CellY(frame.y0 + (step.cell.y + 0.5) * frame.cell)};
  return route;
}

std::vector<Pose2> Se2Planner::CorridorWaypoints(const Pose2& start, const Pose2& goal) const {
  std::vector<Pose2> waypoints;
  if (!(options_.heuristic_turn_cost > 0.0)) return waypoints;
  const std::vector<RouteStep> route = Route(start, goal, options_.heuristic_turn_cost, /*coarse=*/false);
  // The runs of steps with one heading, as [first, end) indices.
  std::vector<std::pair<size_t, size_t>> runs;
  for (size_t i = 0; i < route.size(); ++i)
    if (runs.empty() || route[i].heading != route[runs.back().first].heading)
      runs.push_back({i, i + 1});
    else
      runs.back().second = i + 1;
  // A waypoint in the middle of every straight run along x or y between the first and the
  // last, centred across the corridor, with the run's heading.
  const double min_run = 2.0 * options_.turn_radius;
  for (size_t i = 1; i + 1 < runs.size(); ++i) {
    const auto [first, end] = runs[i];
    const int heading = route[first].heading;
    if (heading % 2 == 1 || static_cast<double>(end - first) * field_->frame().cell < min_run) continue;
    const Pose2 w = CentredPose(route[first + (end - first) / 2].cell, heading);
    if (checker_->Collides(w)) continue;
    waypoints.push_back(w);
  }
  return waypoints;
}

std::vector<Pose2> Se2Planner::RouteWaypoints(const Pose2& start, const Pose2& goal) const {
  std::vector<Pose2> waypoints;
  const std::vector<RouteStep> route = Route(start, goal, options_.corridor_route_turn_cost, /*coarse=*/true);
  // Route steps are route_grid_ cells; the walk into a side arm is in the field's cells.
  const size_t lead = static_cast<size_t>(std::lround(options_.corridor_route_lead / route_grid_.frame.cell));
  const size_t arm_cells = static_cast<size_t>(std::lround(options_.corridor_route_lead / field_->frame().cell));
  const auto add = [&](GridCell cell, int heading) {
    const Pose2 w = CentredPose(cell, heading);
    if (!checker_->Collides(w)) waypoints.push_back(w);
  };
  using H = LazyHeadingGridDistances;
  // The sense of the route's move into step i: forward when along its heading.
  const auto forward_at = [&](size_t i) {
    const GridCell a = route[i > 0 ? i - 1 : 0].cell, b = route[i].cell;
    const int k = route[i].heading;
    return (b.x - a.x) * H::kDx[k] + (b.y - a.y) * H::kDy[k] >= 0;
  };
  for (const RouteTurn& turn : RouteTurns(route, lead)) {
    if (turn.before > 0) add(route[turn.before].cell, route[turn.before].heading);
    // Where the route changes between forward and reverse it turns in place at the crossing,
    // which the vehicle does not fit to do: the real maneuver has a cusp in an arm of the
    // crossing, so a waypoint `lead` into the first free arm, as the vehicle enters it
    // (forward: facing into it; in reverse: facing out), splits it into two turns.
    const GridCell at = route[turn.first - 1].cell;
    const int in = route[turn.first - 1].heading, out = route[turn.after].heading;
    const bool forward_in = forward_at(turn.first - 1), forward_out = forward_at(turn.after);
    if (forward_in != forward_out) {
      // Arms by the direction the vehicle drives into them; not the one it came from.
      const int travel_in = forward_in ? in : (in + 4) % 8;
      const int first_arm = forward_in ? out : (out + 4) % 8;
      for (const int arm : {first_arm, (first_arm + 2) % 8, (first_arm + 6) % 8}) {
        if (arm == (travel_in + 4) % 8 || arm % 2 == 1) continue;
        GridCell c = CentredCell(at, arm);  // from the middle of the crossing across the arm
        bool free = true;
        for (size_t j = 0; j < arm_cells && free; ++j) {
          c = {c.x + H::kDx[arm], c.y + H::kDy[arm]};
          free = centre_cells_.Free(c.x, c.y);
        }
        if (!free) continue;
        const Pose2 w = CentredPose(c, forward_in ? arm : (arm + 4) % 8);
        if (checker_->Collides(w)) continue;
        waypoints.push_back(w);
        break;
      }
    }
    if (turn.after + 1 < route.size()) add(route[turn.after].cell, route[turn.after].heading);
  }
  return waypoints;
}

namespace {

// The work of another search added to a result's counters (states: the larger).
void AddCounts(Se2PlanResult& into, const Se2PlanResult& other) {
  into.expansions += other.expansions;
  into.states = std::max(into.states, other.states);
  into.memory_bytes = std::max(into.memory_bytes, other.memory_bytes);
  into.shots_tried += other.shots_tried;
  into.collisions.free_by_field += other.collisions.free_by_field;
  into.collisions.blocked_by_field += other.collisions.blocked_by_field;
  into.collisions.exact_tests += other.collisions.exact_tests;
}

}  // namespace

Se2PlanResult Se2Planner::Plan(const Pose2& start, const Pose2& goal, const SearchLimits& limits) const {
  const bool waypoints_on = options_.corridor_waypoints && options_.heuristic_turn_cost > 0.0;
  const bool route_on = options_.corridor_route && Finite(start) && Finite(goal) &&
                        std::hypot(goal.x - start.x, goal.y - start.y) >= options_.corridor_route_min_distance;
  if (!setup_error_.empty() || (!waypoints_on && !route_on)) return Search(start, goal, limits);
  // The shot from the start first: where it is free (a box cut, a whole entry) neither the
  // (cell, heading) costs behind the waypoints nor a leg is needed.
  const Se2PlanResult direct = Search(start, goal, limits, /*shot_only=*/true);
  if (direct.status != SearchStatus::kNoPath) return direct;
  Se2PlanResult spent;  // the work of the attempts that gave way
  if (route_on) {
    Se2PlanResult routed = PlanThrough(start, RouteWaypoints(start, goal), goal, limits,
                                       options_.corridor_turn_expansions);
    if (routed.status == SearchStatus::kFound || routed.status == SearchStatus::kStopped) return routed;
    AddCounts(spent, routed);
  }
  Se2PlanResult r;
  if (waypoints_on) {
    SearchLimits rest = limits;
    rest.max_expansions = std::max<int64_t>(1, limits.max_expansions - spent.expansions);
    r = PlanThrough(start, CorridorWaypoints(start, goal), goal, rest, options_.corridor_leg_expansions);
    if (r.status != SearchStatus::kFound && r.status != SearchStatus::kStopped) {
      AddCounts(spent, r);
      r = {};
    }
  }
  if (r.expansions == 0 && r.status != SearchStatus::kFound) {
    SearchLimits rest = limits;
    rest.max_expansions = std::max<int64_t>(1, limits.max_expansions - spent.expansions);
    r = Search(start, goal, rest);
  }
  AddCounts(r, spent);
  return r;
}

Se2PlanResult Se2Planner::PlanThrough(const Pose2& start, const std::vector<Pose2>& waypoints, const Pose2& goal,
                                      const SearchLimits& limits, int64_t leg_expansions) const {
  Se2PlanResult total;
  if (waypoints.empty()) return total;  // kNoPath, no work: the caller searches the whole
  // Leg by leg; the first leg that fails gives way (kNoPath with the legs' work counted).
  total.status = SearchStatus::kFound;
  total.path.start = start;
  std::vector<MotionPiece> pieces;
  Pose2 from = start;
  for (size_t i = 0; i <= waypoints.size(); ++i) {
    const Pose2 to = i < waypoints.size() ? waypoints[i] : goal;
    SearchLimits leg = limits;
    leg.max_expansions = std::min<int64_t>(leg_expansions, limits.max_expansions - total.expansions);
    Se2PlanResult r;
    if (leg.max_expansions >= 1) r = Search(from, to, leg);
    if (r.status == SearchStatus::kStopped && r.expansions < leg.max_expansions) {
      AddCounts(r, total);  // stopped by the caller (deadline, states), not by the leg's budget
      return r;
    }
    AddCounts(total, r);
    if (r.status != SearchStatus::kFound) {
      total.status = SearchStatus::kNoPath;
      total.reason = "a corridor leg failed";
      total.path = {};
      return total;
    }
    total.cost += r.cost;
    pieces.insert(pieces.end(), r.path.pieces.begin(), r.path.pieces.end());
    from = to;
  }
  total.path.pieces = MergePieces(pieces);
  return total;
}

Se2PlanResult Se2Planner::Search(const Pose2& start_in, const Pose2& goal_in, const SearchLimits& limits,
                                 bool shot_only) const {
  Se2PlanResult result;
  const auto invalid = [&](const std::string& reason) {
    result.status = SearchStatus::kInvalidRequest;
    result.reason = reason;
    return result;
  };
  if (!setup_error_.empty()) return invalid(setup_error_);
  const Pose2 start(start_in.x, start_in.y, NormalizeAngle(start_in.theta));
  const Pose2 goal(goal_in.x, goal_in.y, NormalizeAngle(goal_in.theta));
  if (!Finite(start_in)) return invalid(CheckPose(start_in, "start"));
  if (!Finite(goal_in)) return invalid(CheckPose(goal_in, "goal"));
  const double margin = checker_->margin(), slack = field_->Slack();
  if (largest_clearance_ + slack < checker_->inscribed_radius() + margin) {
    std::ostringstream s;
    s << "the footprint fits nowhere in the map: its centre needs " << checker_->inscribed_radius() + margin
      << " m to the nearest wall, the map has at most " << largest_clearance_ + slack << " m";
    return invalid(s.str());
  }
  for (const auto& [pose, what] : {std::pair{start, "start"}, std::pair{goal, "goal"}}) {
    const std::string problem = CheckPose(pose, what);
    if (!problem.empty()) return invalid(problem);
  }
  const CollisionCounters before = checker_->counters();
  const auto finish = [&](SearchStatus status, std::string reason) {
    result.status = status;
    result.reason = std::move(reason);
    const CollisionCounters& now = checker_->counters();
    result.collisions = {now.free_by_field - before.free_by_field, now.blocked_by_field - before.blocked_by_field,
                         now.exact_tests - before.exact_tests};
    return result;
  };

  const MotionCosts& costs = options_.costs;
  const double r = options_.turn_radius;
  // The analytic shot from `pose`: the cheapest obstacle-free shots that are short enough,
  // cheapest first; the first free one (in `tried`), or null. A shot's pieces are built only
  // when it is tried.
  std::optional<AnalyticShot> tried;
  // A shot that collides mostly does so far from where it starts, which a sweep from its start
  // reaches last: poses kCoarseShotSpacing apart along each piece (for any point of the
  // polygon) and each piece's end are looked at first, so a shot blocked there costs a few
  // checks, not a sweep up to the wall; then the pieces are swept. The last end is the goal,
  // checked free with the request.
  const double rc = checker_->circumscribed_radius();
  const auto blocked_coarsely = [&](const Pose2& pose, const AnalyticShot& shot) {
    Pose2 from = pose;
    for (size_t k = 0; k < shot.pieces.size(); ++k) {
      const MotionPiece& p = shot.pieces[k];
      const int m = std::max(1, static_cast<int>(std::ceil(Sweep(p, rc) / kCoarseShotSpacing)));
      const PieceSampler along(from, p.motion, p.radius);
      for (int i = 1; i < m; ++i) {
        const PieceSampler::Sample q = along.At(p.amount * static_cast<double>(i) / m);
        if (checker_->Check(q.pose, q.cos_theta, q.sin_theta).collides) return true;
      }
      if (k + 1 < shot.pieces.size() && !PoseFree(p.end)) return true;
      from = p.end;
    }
    return false;
  };
  const auto free_shot = [&](const Pose2& pose, int direction) -> const AnalyticShot* {
    const ShotCandidates candidates(pose, goal, r, costs, direction);
    for (int i = 0; i < candidates.size(); ++i) {
      if (candidates.cost(i) > options_.analytic_shot_max_cost_ratio * candidates.cost(0)) break;  // cheapest first
      tried = candidates.Build(i);
      if (!tried) continue;
      double length = 0.0;
      for (const MotionPiece& p : tried->pieces) length += p.motion == Motion::kTurnInPlace ? 0.0 : p.amount;
      if (length > options_.analytic_shot_max_length) continue;
      ++result.shots_tried;
      if (blocked_coarsely(pose, *tried)) continue;
      bool free = true;
      Pose2 from = pose;
      for (const MotionPiece& p : tried->pieces) {
        if (PieceCollides(from, p)) {
          free = false;
          break;
        }
        from = p.end;
      }
      if (free) return &*tried;
    }
    return nullptr;
  };
  // The simple case first (thesis 6.2.2: "gradient descent for the simple ones"): the shot
  // from the start, before the 2-D heuristic is settled (a 100 m entry's Dijkstra costs far
  // more than the shot's sweep). It is the shot the search's first expansion would try, so
  // the answer is the search's, only sooner.
  const SearchStatus first = CheckLimits(limits, 0, 1);
  if (first != SearchStatus::kFound) return finish(first, LimitReason(first, 0, 1));
  if (const AnalyticShot* free = free_shot(start, 0)) {
    result.path.start = start;
    result.path.pieces = MergePieces(free->pieces);
    result.cost = free->cost;
    result.expansions = result.states = 1;
    return finish(SearchStatus::kFound, "");
  }
  if (shot_only) return finish(SearchStatus::kNoPath, "no analytic shot from the start is free");

  // 2-D part of the heuristic: distances from the goal over the cells the centre may be in,
  // settled on demand and kept for the next request to the same goal cell.
  const GridFrame& frame = field_->frame();
  // With heuristic_turn_cost the distances are over (cell, axis) and charge the axis's turns;
  // a cell is reachable in one exactly when it is in the other (turns are free of the map).
  const GridCell goal_cell{frame.CellX(goal.x), frame.CellY(goal.y)};
  const bool axis_term = options_.heuristic_turn_cost > 0.0;
  LazyGridDistances* to_goal = axis_term ? nullptr : &DistancesTo(goal_cell);
  LazyHeadingGridDistances* to_goal_axis =
      axis_term ? &HeadingDistancesTo(goal_cell, LazyHeadingGridDistances::HeadingOf(goal.theta), options_.heuristic_turn_cost) : nullptr;
  const auto distance_2d = [&](double x, double y, double theta) {
    const double d = axis_term ? to_goal_axis->Distance(frame.CellX(x), frame.CellY(y), LazyHeadingGridDistances::HeadingOf(theta))
                               : to_goal->Distance(frame.CellX(x), frame.CellY(y));
    return d == kInf ? kInf : std::max(0.0, d * frame.cell / (options_.shot_heuristic ? 1.0 : kOctileStretch) - 2.0 * slack);
  };
  if (distance_2d(start.x, start.y, start.theta) == kInf)
    return finish(SearchStatus::kNoPath,
                  "the goal is not reachable: no corridor wide enough for the footprint's inscribed circle joins "
                  "start and goal");
  const auto heuristic = [&](const Pose2& p, int direction) {
    const double d2 = distance_2d(p.x, p.y, p.theta);
    if (d2 == kInf) return kInf;
    double free_space = FreeSpaceLowerBound(p, goal, r, costs);
    if (options_.shot_heuristic) {
      const double shot = CheapestShotCost(p, goal, r, costs, direction);
      if (shot < kInf) free_space = std::max(free_space, shot);
    }
    return std::max(d2, free_space);
  };

  const int bins = options_.heading_bins;
  const double bin = 2.0 * kPi / bins;
  const auto primitives = Primitives(r, bin);
  const std::vector<SweptPrimitive>& swept = PrimitivesFor(start.theta);
  const auto key = [&](double x, double y, int heading) {
    const auto cell = [](double v, double res) {
      return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / res)) & 0x1FFFFF);
    };
    return (cell(x, options_.xy_resolution) << 42) | (cell(y, options_.xy_resolution) << 21) |
           static_cast<uint64_t>(heading);
  };
  const int goal_heading =
      (static_cast<int>(std::lround(NormalizeAngle(goal.theta - start.theta) / bin)) % bins + bins) % bins;
  const uint64_t goal_key = key(goal.x, goal.y, goal_heading);

  std::vector<Node> nodes;
  nodes.reserve(1024);
  StateTable best(1024);  // state cell -> its best node
  // The open list: a binary heap (std::priority_queue's own push_heap / pop_heap) in a vector
  // whose capacity the result's memory counts.
  std::vector<OpenEntry> open;
  open.reserve(1024);
  const auto push = [&](const OpenEntry& entry) {
    open.push_back(entry);
    std::push_heap(open.begin(), open.end());
  };
  const auto stored = [&] {
    result.states = static_cast<int64_t>(nodes.size());
    result.memory_bytes = static_cast<int64_t>(nodes.capacity() * sizeof(Node) + best.bytes() +
                                               open.capacity() * sizeof(OpenEntry));
  };
  const PoseCheck at_start = checker_->Check(start);
  nodes.push_back({start.x, start.y, 0.0, -1, SpareDown(at_start.spare), 0, -1, 0, false});
  best.Set(key(start.x, start.y, 0), 0);
  push({heuristic(start, 0), 0.0, 0});
  const auto pose_of = [&](const Node& n) {
    return n.primitive < 0 ? start : Pose2(n.x, n.y, NormalizeAngle(start.theta + n.heading * bin));
  };

  const auto path_to = [&](int32_t n, const std::vector<MotionPiece>& tail) {
    std::vector<MotionPiece> pieces;
    for (int32_t i = n; nodes[static_cast<size_t>(i)].parent != -1; i = nodes[static_cast<size_t>(i)].parent) {
      const Node& node = nodes[static_cast<size_t>(i)];
      const MotionPiece& step = primitives[static_cast<size_t>(node.primitive)];
      pieces.push_back({step.motion, step.amount, step.radius, pose_of(node)});
    }
    std::reverse(pieces.begin(), pieces.end());
    pieces.insert(pieces.end(), tail.begin(), tail.end());
    PlannedPath path;
    path.start = start;
    path.pieces = MergePieces(pieces);
    return path;
  };

  while (!open.empty()) {
    std::pop_heap(open.begin(), open.end());
    const OpenEntry e = open.back();
    open.pop_back();
    Node& current = nodes[static_cast<size_t>(e.node)];
    if (current.closed) continue;
    const SearchStatus limit = CheckLimits(limits, result.expansions, static_cast<int64_t>(nodes.size()));
    if (limit != SearchStatus::kFound) {
      stored();
      return finish(limit, LimitReason(limit, result.expansions, result.states));
    }
    current.closed = true;
    ++result.expansions;
    const Pose2 pose = pose_of(current);
    const double g = current.g, spare = current.spare;
    const int direction = current.direction, heading = current.heading;

    // The analytic shot (the start's was tried before the search).
    if (e.node != 0 && (result.expansions % options_.analytic_shot_interval == 1 ||
                        options_.analytic_shot_interval == 1 || key(pose.x, pose.y, heading) == goal_key)) {
      if (const AnalyticShot* free = free_shot(pose, direction)) {
        result.path = path_to(e.node, free->pieces);
        result.cost = g + free->cost;
        stored();
        return finish(SearchStatus::kFound, "");
      }
    }

    for (int m = 0; m < kPrimitives; ++m) {
      const MotionPiece& primitive = primitives[static_cast<size_t>(m)];
      const SweptPrimitive& sweep = swept[static_cast<size_t>(heading * kPrimitives + m)];
      const SweptPose& end = sweep.poses.back();
      const Pose2 next(pose.x + end.dx, pose.y + end.dy, end.theta);
      const uint64_t k = key(next.x, next.y, sweep.end_heading);
      const int d = DriveDirection(primitive.motion);
      const double ng = g + PieceCost(primitive, direction, costs);
      if (const int32_t seen = best.Find(k); seen >= 0) {
        const Node& other = nodes[static_cast<size_t>(seen)];
        if (other.closed || other.g <= ng) continue;
      }
      double next_spare = 0.0;
      const auto check = [&](int i) {
        const SweptPose& q = sweep.poses[static_cast<size_t>(i - 1)];
        return checker_->Check(Pose2(pose.x + q.dx, pose.y + q.dy, q.theta), q.cos_theta, q.sin_theta);
      };
      if (SweepCollides(static_cast<int>(sweep.poses.size()), sweep.spacing, options_.collision_step, spare, check,
                        &next_spare))
        continue;
      const int8_t next_direction = static_cast<int8_t>(d != 0 ? d : direction);
      const double h = heuristic(next, next_direction);
      if (h == kInf) continue;
      const int32_t index = static_cast<int32_t>(nodes.size());
      nodes.push_back({next.x, next.y, ng, e.node, SpareDown(next_spare), static_cast<int16_t>(sweep.end_heading),
                       static_cast<int8_t>(m), next_direction, false});
      best.Set(k, index);
      push({ng + h, ng, index});
    }
  }
  stored();
  return finish(SearchStatus::kNoPath, "the goal is not reachable: every pose the footprint can reach from the start (" +
                                           std::to_string(result.expansions) + " expanded) was searched");
}

}  // namespace minenav
