#include "planner/se2_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <sstream>
#include <unordered_map>

#include "common/config.h"
#include "planner/analytic_shot.h"
#include "planner/grid_dijkstra.h"

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

struct Node {
  Pose2 pose;
  double g = 0.0;
  int32_t parent = -1;
  Motion motion = Motion::kForward;  // the step that reached it
  double amount = 0.0;
  int8_t direction = 0;  // last drive direction on the way here (+1, -1, 0 none yet)
  bool closed = false;
};

struct OpenEntry {
  double f;
  int32_t node;
  bool operator<(const OpenEntry& o) const { return f > o.f; }
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
  scope.AddInt("analytic_shot_interval", &o.analytic_shot_interval, "expansions between analytic shots", 1, 1000000);
  scope.AddDouble("analytic_shot_max_length", &o.analytic_shot_max_length, "m", "longer analytic shots are not tried",
                  0.0, 1e6);
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
  walls_ = std::make_unique<StaticSegmentIndex>(walls);
  const double margin = options_.clearance + 0.5 * options_.collision_step;
  const GridFrame frame = GridFrame::Covering(lo, hi, options_.field_resolution, 0.0);
  const double slack = 0.5 * std::sqrt(2.0) * options_.field_resolution;
  field_ = std::make_unique<ClearanceField>(walls, frame, CircumscribedRadius(footprint_) + margin + 3.0 * slack);
  checker_ = std::make_unique<FootprintCollisionChecker>(*walls_, *field_, footprint_, margin);
  centre_cells_ = OccupancyGrid(frame.nx, frame.ny);
  for (int iy = 0; iy < frame.ny; ++iy)
    for (int ix = 0; ix < frame.nx; ++ix) {
      const double c = field_->AtCell(ix, iy);
      largest_clearance_ = std::max(largest_clearance_, c);
      centre_cells_.SetBlocked(ix, iy, c + slack < checker_->inscribed_radius() + margin);
    }
}

bool Se2Planner::PoseFree(const Pose2& pose) const { return checker_ && !checker_->Collides(pose); }

bool Se2Planner::PieceCollides(const Pose2& from, const MotionPiece& piece) const {
  const double rc = checker_->circumscribed_radius();
  double sweep = piece.amount;  // m the farthest point of the polygon moves
  if (piece.motion == Motion::kTurnInPlace)
    sweep = rc * std::abs(piece.amount);
  else if (IsArc(piece.motion))
    sweep = piece.amount * (piece.radius + rc) / piece.radius;
  const int n = std::max(1, static_cast<int>(std::ceil(sweep / options_.collision_step)));
  for (int k = 1; k <= n; ++k) {
    const double f = static_cast<double>(k) / n;
    if (checker_->Collides(PoseAfter(from, piece.motion, piece.amount * f, piece.radius))) return true;
  }
  return false;
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

Se2PlanResult Se2Planner::Plan(const Pose2& start_in, const Pose2& goal_in, const SearchLimits& limits) const {
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

  // 2-D part of the heuristic: distances from the goal over the cells the centre may be in.
  const GridFrame& frame = field_->frame();
  const GridCell goal_cell{frame.CellX(goal.x), frame.CellY(goal.y)};
  const std::vector<double> cells_to_goal = GridDistancesFrom(centre_cells_, goal_cell);
  const auto distance_2d = [&](const Pose2& p) {
    const int ix = frame.CellX(p.x), iy = frame.CellY(p.y);
    if (!frame.Contains(ix, iy)) return kInf;
    const double d = cells_to_goal[centre_cells_.Index(ix, iy)];
    return d == kInf ? kInf : std::max(0.0, d * frame.cell - 2.0 * slack);
  };
  if (distance_2d(start) == kInf)
    return finish(SearchStatus::kNoPath,
                  "the goal is not reachable: no corridor wide enough for the footprint's inscribed circle joins "
                  "start and goal");
  const MotionCosts& costs = options_.costs;
  const double r = options_.turn_radius;
  const auto heuristic = [&](const Pose2& p, int direction) {
    const double d2 = distance_2d(p);
    if (d2 == kInf) return kInf;
    const std::vector<AnalyticShot> shots = AnalyticShots(p, goal, r, costs, direction);
    return std::max(d2, shots.empty() ? 0.0 : shots.front().cost);
  };

  // The motions of one step.
  const double bin = 2.0 * kPi / options_.heading_bins, step = r * bin;
  const MotionPiece primitives[] = {
      {Motion::kForward, step, 0.0, {}},      {Motion::kReverse, step, 0.0, {}},
      {Motion::kArcLeft, step, r, {}},        {Motion::kArcRight, step, r, {}},
      {Motion::kArcLeftReverse, step, r, {}}, {Motion::kArcRightReverse, step, r, {}},
      {Motion::kTurnInPlace, bin, 0.0, {}},   {Motion::kTurnInPlace, -bin, 0.0, {}}};

  const auto key = [&](const Pose2& p) {
    const auto cell = [](double v, double res) {
      return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / res)) & 0x1FFFFF);
    };
    const int h = static_cast<int>(std::lround((p.theta + kPi) / bin)) % options_.heading_bins;
    return (cell(p.x, options_.xy_resolution) << 42) | (cell(p.y, options_.xy_resolution) << 21) |
           static_cast<uint64_t>(h);
  };

  std::vector<Node> nodes;
  std::unordered_map<uint64_t, int32_t> best;  // state cell -> its best node
  std::priority_queue<OpenEntry> open;
  nodes.push_back({start, 0.0, -1, Motion::kForward, 0.0, 0, false});
  best[key(start)] = 0;
  open.push({heuristic(start, 0), 0});

  const auto path_to = [&](int32_t n, const std::vector<MotionPiece>& tail) {
    std::vector<MotionPiece> pieces;
    for (int32_t i = n; nodes[static_cast<size_t>(i)].parent != -1; i = nodes[static_cast<size_t>(i)].parent) {
      const Node& node = nodes[static_cast<size_t>(i)];
      pieces.push_back({node.motion, node.amount, IsArc(node.motion) ? r : 0.0, node.pose});
    }
    std::reverse(pieces.begin(), pieces.end());
    pieces.insert(pieces.end(), tail.begin(), tail.end());
    PlannedPath path;
    path.start = start;
    path.pieces = MergePieces(pieces);
    return path;
  };

  while (!open.empty()) {
    const OpenEntry e = open.top();
    open.pop();
    Node& current = nodes[static_cast<size_t>(e.node)];
    if (current.closed) continue;
    const SearchStatus limit = CheckLimits(limits, result.expansions, static_cast<int64_t>(nodes.size()));
    if (limit != SearchStatus::kFound) {
      result.states = static_cast<int64_t>(nodes.size());
      return finish(limit, "stopped by " + ToString(limit) + " after " + std::to_string(result.expansions) +
                               " expansions and " + std::to_string(nodes.size()) + " states");
    }
    current.closed = true;
    ++result.expansions;
    const Pose2 pose = current.pose;
    const double g = current.g;
    const int direction = current.direction;

    // The analytic shot: the cheapest obstacle-free shots that are short enough, first free one wins.
    if (result.expansions % options_.analytic_shot_interval == 1 || options_.analytic_shot_interval == 1 ||
        key(pose) == key(goal)) {
      for (const AnalyticShot& shot : AnalyticShots(pose, goal, r, costs, direction)) {
        double length = 0.0;
        for (const MotionPiece& p : shot.pieces) length += p.motion == Motion::kTurnInPlace ? 0.0 : p.amount;
        if (length > options_.analytic_shot_max_length) continue;
        ++result.shots_tried;
        bool free = true;
        Pose2 from = pose;
        for (const MotionPiece& p : shot.pieces) {
          if (PieceCollides(from, p)) {
            free = false;
            break;
          }
          from = p.end;
        }
        if (!free) continue;
        result.path = path_to(e.node, shot.pieces);
        result.cost = g + shot.cost;
        result.states = static_cast<int64_t>(nodes.size());
        return finish(SearchStatus::kFound, "");
      }
    }

    for (const MotionPiece& primitive : primitives) {
      const Pose2 next = PoseAfter(pose, primitive.motion, primitive.amount, primitive.radius);
      const uint64_t k = key(next);
      const int d = DriveDirection(primitive.motion);
      const double ng = g + PieceCost(primitive, direction, costs);
      const auto it = best.find(k);
      if (it != best.end()) {
        const Node& other = nodes[static_cast<size_t>(it->second)];
        if (other.closed || other.g <= ng) continue;
      }
      if (PieceCollides(pose, primitive)) continue;
      const int8_t next_direction = static_cast<int8_t>(d != 0 ? d : direction);
      const double h = heuristic(next, next_direction);
      if (h == kInf) continue;
      const int32_t index = static_cast<int32_t>(nodes.size());
      nodes.push_back({next, ng, e.node, primitive.motion, primitive.amount, next_direction, false});
      best[k] = index;
      open.push({ng + h, index});
    }
  }
  result.states = static_cast<int64_t>(nodes.size());
  return finish(SearchStatus::kNoPath, "the goal is not reachable: every pose the footprint can reach from the start (" +
                                           std::to_string(result.expansions) + " expanded) was searched");
}

}  // namespace minenav
