// The SE(2) planner (planner/se2_planner.h) side by side with OMPL (Debian's libompl-dev) on
// the same requests: the scenarios of bench/planner_scenarios.h (issue 13, "Measured", second
// bullet; planner/README.md, "Against OMPL"). OMPL is used here only, never by the planner.
//
// Both sides get the same map, footprint and collision checking:
//   state space   ompl::base::ReedsSheppStateSpace with our turning radius (forward and
//                 reverse arcs at R and straights: our motions less the turn in place), bounded
//                 by the map's box;
//   states        valid when Se2Planner::PoseFree (same polygon, same clearance);
//   motions       a MotionValidator that turns the Reeds-Shepp curve between two states into
//                 our MotionPieces and asks Se2Planner::PieceCollides for each: the very sweep
//                 our search uses (poses no farther apart than collision_step for any point of
//                 the polygon, the field's quick decisions, the exact test between);
//   objective     path length (ompl::base::PathLengthOptimizationObjective: metres driven).
// Planners (OMPL's defaults otherwise): RRT* (ompl::geometric::RRTstar) and BIT*
// (ompl::geometric::BITstar, Gammell et al. 2015: asymptotically optimal like RRT*, but it
// searches a batch of samples in order of the admissible Reeds-Shepp distance, like our A*,
// and after the first solution samples only where a shorter path can be: the strongest of
// OMPL's asymptotically optimal planners in its authors' benchmarks).
//
// Per request: our planner plans once (cold, stopped after --deadline s); each OMPL planner
// runs for max(--ompl_time, ours) s, every improvement of its solution recorded through the
// ProblemDefinition's intermediate-solution callback (time and path). Read off that one run:
// (a) the best path within the time our planner took, (b) within --ompl_time, the time to its
// first solution and the time to a path no longer than ours. (The planners do not look at the
// time left, so (a) is what a run stopped then would return.) Times are thread CPU seconds
// (bench_util.h), OMPL's termination condition included. Lengths in metres driven; our turns
// in place count 0 m (OMPL's space has none). Every path, ours and OMPL's (converted to pieces
// exactly: each Reeds-Shepp curve is arcs at R and straights), is judged by the independent
// checker (planner/testing/path_checker.h); a path it rejects counts as a failure.
//
//   planner_ompl_bench [--seeds 2] [--instances 4] [--deadline 2] [--ompl_time 1] [--json_out FILE]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/ReedsSheppStateSpace.h>
#include <ompl/config.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "bench/planner_scenarios.h"
#include "common/config.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/motion_costs.h"
#include "planner/se2_planner.h"
#include "planner/testing/path_checker.h"

namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;
namespace bench = minenav::bench;
using minenav::Motion;
using minenav::MotionPiece;
using minenav::Pose2;
using minenav::Se2Planner;

constexpr double kInf = std::numeric_limits<double>::infinity();
// Debian's ompl/config.h defines OMPL_VERSION as "": the version from its numbers.
const std::string kOmplVersion = std::to_string(OMPL_MAJOR_VERSION) + "." + std::to_string(OMPL_MINOR_VERSION) + "." +
                                 std::to_string(OMPL_PATCH_VERSION);
const char* const kOmplPlanners[] = {"RRTstar", "BITstar"};

Pose2 ToPose(const ob::State* s) {
  const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
  return {se2->getX(), se2->getY(), se2->getYaw()};
}

// The Reeds-Shepp curve OMPL drives from a to b as our pieces, from `from` (a's pose).
std::vector<MotionPiece> RsPieces(const ob::ReedsSheppStateSpace& space, double radius, const ob::State* a,
                                  const ob::State* b) {
  const ob::ReedsSheppStateSpace::ReedsSheppPath rs = space.reedsShepp(a, b);
  std::vector<MotionPiece> pieces;
  Pose2 at = ToPose(a);
  for (int i = 0; i < 5; ++i) {
    const auto type = rs.type_[i];
    if (type == ob::ReedsSheppStateSpace::RS_NOP) break;
    const double s = rs.length_[i] * radius;  // OMPL's lengths are in turning radii, signed
    if (std::abs(s) < 1e-9) continue;
    const bool forward = s > 0.0;
    Motion m = forward ? Motion::kForward : Motion::kReverse;
    if (type == ob::ReedsSheppStateSpace::RS_LEFT) m = forward ? Motion::kArcLeft : Motion::kArcLeftReverse;
    if (type == ob::ReedsSheppStateSpace::RS_RIGHT) m = forward ? Motion::kArcRight : Motion::kArcRightReverse;
    MotionPiece p;
    p.motion = m;
    p.amount = std::abs(s);
    p.radius = type == ob::ReedsSheppStateSpace::RS_STRAIGHT ? 0.0 : radius;
    p.end = minenav::PoseAfter(at, m, p.amount, p.radius);
    at = p.end;
    pieces.push_back(p);
  }
  return pieces;
}

// OMPL's motion check = our planner's sweep of each piece of the Reeds-Shepp curve.
class PieceMotionValidator : public ob::MotionValidator {
 public:
  PieceMotionValidator(const ob::SpaceInformationPtr& si, const Se2Planner& planner)
      : ob::MotionValidator(si),
        planner_(planner),
        space_(*si->getStateSpace()->as<ob::ReedsSheppStateSpace>()),
        radius_(planner.options().turn_radius) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    Pose2 at = ToPose(s1);
    for (const MotionPiece& p : RsPieces(space_, radius_, s1, s2)) {
      if (planner_.PieceCollides(at, p)) {
        ++invalid_;
        return false;
      }
      at = p.end;
    }
    ++valid_;
    return true;
  }

  // The last valid state and its fraction of the curve: sampled with PoseFree at the centre
  // spacing that moves no point of the polygon more than collision_step (OMPL's planners
  // used here call only the other overload).
  bool checkMotion(const ob::State* s1, const ob::State* s2, std::pair<ob::State*, double>& last_valid) const override {
    const double length = si_->distance(s1, s2);
    const double rc = minenav::CircumscribedRadius(planner_.footprint());
    const double step = planner_.options().collision_step * radius_ / (radius_ + rc);
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    ob::State* s = si_->allocState();
    for (int i = 1; i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      space_.interpolate(s1, s2, t, s);
      if (planner_.PoseFree(ToPose(s))) continue;
      const double t_ok = static_cast<double>(i - 1) / n;
      if (last_valid.first) space_.interpolate(s1, s2, t_ok, last_valid.first);
      last_valid.second = t_ok;
      si_->freeState(s);
      ++invalid_;
      return false;
    }
    si_->freeState(s);
    ++valid_;
    return true;
  }

 private:
  const Se2Planner& planner_;
  const ob::ReedsSheppStateSpace& space_;
  double radius_;
};

struct PathSummary {
  bool found = false, checked = false;
  double length = kInf, cost = kInf;
  int reversals = 0;
  std::string problem;
};

// Length, MotionCosts cost, reversals and the independent checker's verdict of pieces from start.
PathSummary Summarise(const Se2Planner& planner, const std::vector<minenav::Segment>& map, const Pose2& start,
                      const std::vector<MotionPiece>& pieces) {
  PathSummary s;
  s.found = true;
  minenav::PlannedPath path;
  path.start = start;
  path.pieces = pieces;
  s.length = path.Length();
  s.reversals = path.Reversals();
  s.cost = 0.0;
  int direction = 0;
  for (const MotionPiece& p : pieces) {
    s.cost += minenav::PieceCost(p, direction, planner.options().costs);
    if (minenav::DriveDirection(p.motion) != 0) direction = minenav::DriveDirection(p.motion);
  }
  minenav::testing::PathCheckSettings st;
  st.polygon = planner.footprint().vertices;
  st.turn_radius = planner.options().turn_radius;
  st.clearance = planner.options().clearance;
  st.sample_step = 0.02;
  std::vector<minenav::testing::CheckedPiece> checked;
  for (const MotionPiece& p : pieces) checked.push_back({static_cast<int>(p.motion), p.end});
  const auto report = minenav::testing::CheckPath(map, start, checked, st);
  s.checked = report.ok;
  s.problem = report.problem;
  return s;
}

struct Improvement {
  double t = 0.0;       // s after the planner started
  double length = 0.0;  // m, OMPL's cost of the solution
  std::vector<Pose2> states;
};

struct OmplOutcome {
  std::vector<Improvement> trace;
  double ran_s = 0.0;
  double budget_s = 0.0;                      // the time our planner took
  int at_budget = -1, at_limit = -1;          // index into trace: best path within budget_s, ompl_time
  double first_s = kInf, to_ours_s = kInf;    // time to the first path, to one no longer than ours
  PathSummary budget, limit;
  double max_gap = 0.0;  // m or rad, the converted pieces' ends against OMPL's states
};

// Runs `name` on the request until max(budget, limit) s of thread CPU.
OmplOutcome RunOmpl(const std::string& name, const Se2Planner& planner, const std::vector<minenav::Segment>& map,
                    const bench::PlannerRequest& q, double budget, double limit, double ours_length) {
  const double radius = planner.options().turn_radius;
  auto space = std::make_shared<ob::ReedsSheppStateSpace>(radius);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, planner.map_min().x());
  bounds.setLow(1, planner.map_min().y());
  bounds.setHigh(0, planner.map_max().x());
  bounds.setHigh(1, planner.map_max().y());
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&planner](const ob::State* s) { return planner.PoseFree(ToPose(s)); });
  si->setMotionValidator(std::make_shared<PieceMotionValidator>(si, planner));
  si->setup();

  ob::ScopedState<ob::SE2StateSpace> start(space), goal(space);
  start->setXY(q.start.x, q.start.y);
  start->setYaw(q.start.theta);
  goal->setXY(q.goal.x, q.goal.y);
  goal->setYaw(q.goal.theta);
  // OMPL's headings are in [-pi, pi), ours in (-pi, pi]: a heading of pi is out of its bounds.
  space->enforceBounds(start.get());
  space->enforceBounds(goal.get());
  if (!si->isValid(start.get()) || !si->isValid(goal.get()))
    std::fprintf(stderr, "%s: the start or the goal is not valid for OMPL\n", name.c_str());
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 1e-3);
  pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));

  OmplOutcome o;
  o.budget_s = budget;
  double t0 = 0.0;
  // The callback's states come in the planner's own order, with or without the start and the
  // goal: keep the order whose curve length is the reported cost.
  pdef->setIntermediateSolutionCallback(
      [&](const ob::Planner*, const std::vector<const ob::State*>& states, const ob::Cost cost) {
        const double t = bench::Now() - t0;
        std::vector<const ob::State*> best;
        double best_error = kInf;
        for (const bool reversed : {false, true}) {
          std::vector<const ob::State*> seq = states;
          if (reversed) std::reverse(seq.begin(), seq.end());
          if (seq.empty() || si->distance(seq.front(), start.get()) > 1e-9) seq.insert(seq.begin(), start.get());
          if (si->distance(seq.back(), goal.get()) > 1e-9) seq.push_back(goal.get());
          double length = 0.0;
          for (size_t i = 1; i < seq.size(); ++i) length += si->distance(seq[i - 1], seq[i]);
          const double error = std::abs(length - cost.value());
          if (error < best_error) best_error = error, best = seq;
        }
        Improvement imp;
        imp.t = t;
        imp.length = cost.value();
        for (const ob::State* s : best) imp.states.push_back(ToPose(s));
        if (best_error > 1e-6 * std::max(1.0, cost.value()))
          std::fprintf(stderr, "%s: the reported path (%.3f m) is not its cost (%.3f m)\n", name.c_str(),
                       cost.value() + best_error, cost.value());
        o.trace.push_back(std::move(imp));
      });

  ob::PlannerPtr p;
  if (name == "RRTstar")
    p = std::make_shared<og::RRTstar>(si);
  else
    p = std::make_shared<og::BITstar>(si);
  const double run_s = std::max(budget, limit);
  t0 = bench::Now();
  p->setProblemDefinition(pdef);
  p->setup();
  // Thread CPU time, and a wall-clock cap: a planner that waits (BIT* sleeps while it has no
  // valid goal) spends no CPU, and the bench must not hang.
  const auto wall_end = std::chrono::steady_clock::now() + std::chrono::duration<double>(10.0 * run_s + 10.0);
  const ob::PlannerStatus status = p->solve(ob::PlannerTerminationCondition(
      [&] { return bench::Now() - t0 > run_s || std::chrono::steady_clock::now() > wall_end; }));
  o.ran_s = bench::Now() - t0;
  // An exact solution the callback did not report (it should not happen): record it at the end.
  if (status == ob::PlannerStatus::EXACT_SOLUTION && pdef->hasExactSolution() &&
      (o.trace.empty() || pdef->getSolutionPath()->length() < o.trace.back().length - 1e-6)) {
    std::fprintf(stderr, "%s: a solution not reported by the callback\n", name.c_str());
    auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
    Improvement imp;
    imp.t = o.ran_s;
    imp.length = path->length();
    for (const ob::State* s : path->getStates()) imp.states.push_back(ToPose(s));
    o.trace.push_back(std::move(imp));
  }

  for (size_t i = 0; i < o.trace.size(); ++i) {
    const Improvement& imp = o.trace[i];
    if (imp.t <= budget) o.at_budget = static_cast<int>(i);
    if (imp.t <= limit) o.at_limit = static_cast<int>(i);
    o.first_s = std::min(o.first_s, imp.t);
    if (imp.length <= ours_length + 1e-6) o.to_ours_s = std::min(o.to_ours_s, imp.t);
  }
  // The pieces of a trace entry, checked against OMPL's own states (the conversion's error).
  auto pieces_of = [&](const Improvement& imp) {
    std::vector<MotionPiece> pieces;
    ob::ScopedState<ob::SE2StateSpace> a(space), b(space);
    for (size_t i = 1; i < imp.states.size(); ++i) {
      a->setXY(imp.states[i - 1].x, imp.states[i - 1].y);
      a->setYaw(imp.states[i - 1].theta);
      b->setXY(imp.states[i].x, imp.states[i].y);
      b->setYaw(imp.states[i].theta);
      std::vector<MotionPiece> edge = RsPieces(*space, radius, a.get(), b.get());
      if (edge.empty()) continue;
      const Pose2& end = edge.back().end;
      const Pose2& want = imp.states[i];
      o.max_gap = std::max({o.max_gap, std::hypot(end.x - want.x, end.y - want.y),
                            std::abs(minenav::NormalizeAngle(end.theta - want.theta))});
      edge.back().end = want;
      pieces.insert(pieces.end(), edge.begin(), edge.end());
    }
    return pieces;
  };
  if (o.at_budget >= 0) o.budget = Summarise(planner, map, q.start, pieces_of(o.trace[static_cast<size_t>(o.at_budget)]));
  if (o.at_limit >= 0) {
    o.limit = o.at_limit == o.at_budget ? o.budget
                                        : Summarise(planner, map, q.start, pieces_of(o.trace[static_cast<size_t>(o.at_limit)]));
  }
  return o;
}

struct OursOutcome {
  double s = 0.0;
  std::string status;
  PathSummary path;
};

double MedianOf(const std::vector<double>& v) { return v.empty() ? std::nan("") : bench::Median(v); }

// JSON has no infinity or NaN: null.
nlohmann::json Num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

int Run(int argc, char** argv) {
  int seeds = 2, instances = 4, ompl_seed = 1;
  double deadline = 2.0, ompl_time = 1.0, displacement = 0.1, clearance = 0.05, room = 6.0;
  std::string json_out;
  minenav::ConfigSchema schema("planner_ompl_bench",
                               "The SE(2) planner against OMPL's RRT* and BIT* (Reeds-Shepp space) on the mine's maneuvers.");
  schema.AddInt("seeds", &seeds, "synthetic mines (seeds 1..n)", 1, 100);
  schema.AddInt("instances", &instances, "requests per scenario and mine", 1, 100);
  schema.AddDouble("deadline", &deadline, "s", "CPU time after which our planner's request is stopped", 0.01, 1000.0);
  schema.AddDouble("ompl_time", &ompl_time, "s", "CPU time of each OMPL run (at least as long as ours took)", 0.01,
                   1000.0);
  schema.AddInt("ompl_seed", &ompl_seed, "OMPL's random seed (set once, before the first run)", 1, 1 << 30);
  schema.AddDouble("displacement", &displacement, "m", "the mine walls' fractal midpoint displacement (sim/mine_generator.h)",
                   0.0, 1.0);
  schema.AddDouble("clearance", &clearance, "m", "clearance of both planners", 0.0, 1.0);
  schema.AddDouble("room_width", &room, "m", "the entries' and crosscuts' width (bench/planner_scenarios.h)", 4.0, 20.0);
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(static_cast<std::uint_fast32_t>(ompl_seed));

  const minenav::Footprint miner = minenav::Footprint::Rectangle(3.3, 10.0);
  minenav::Se2PlannerOptions options;
  options.clearance = clearance;
  const bench::PlannerScenarios mine = bench::BuildPlannerScenarios(seeds, instances, displacement, miner, options, room);
  minenav::SearchLimits limits;
  limits.max_expansions = 1'000'000;
  double stop_at = 0.0;
  limits.stop_requested = [&stop_at] { return bench::Now() > stop_at; };

  const size_t n_requests = mine.requests.size();
  std::vector<OursOutcome> ours(n_requests);
  std::vector<std::vector<OmplOutcome>> ompl(n_requests);
  for (size_t i = 0; i < n_requests; ++i) {
    const bench::PlannerRequest& q = mine.requests[i];
    const std::vector<minenav::Segment>& map = mine.maps[mine.MapIndex(q)];
    OursOutcome& o = ours[i];
    const double t0 = bench::Now();
    stop_at = t0 + deadline;
    const minenav::Se2PlanResult r = q.planner->Plan(q.start, q.goal, limits);
    o.s = bench::Now() - t0;
    o.status = minenav::ToString(r.status);
    if (r.status == minenav::SearchStatus::kFound) o.path = Summarise(*q.planner, map, q.start, r.path.pieces);
    if (o.path.found && !o.path.checked)
      std::fprintf(stderr, "%s %zu: ours: checker: %s\n", q.scenario.c_str(), i, o.path.problem.c_str());
    for (const char* name : kOmplPlanners) {
      ompl[i].push_back(RunOmpl(name, *q.planner, map, q, o.s, ompl_time, o.path.found ? o.path.length : -1.0));
      const OmplOutcome& m = ompl[i].back();
      for (const PathSummary* s : {&m.budget, &m.limit})
        if (s->found && !s->checked)
          std::fprintf(stderr, "%s %zu: %s: checker: %s\n", q.scenario.c_str(), i, name, s->problem.c_str());
    }
    std::fprintf(stderr, "%-10s %3zu  ours %-8s %7.1f ms %6.1f m | RRT* first %7.1f ms, %6.1f m at 1 s | BIT* first %7.1f ms, %6.1f m at 1 s\n",
                 q.scenario.c_str(), i, o.status.c_str(), 1e3 * o.s, o.path.length, 1e3 * ompl[i][0].first_s,
                 ompl[i][0].limit.length, 1e3 * ompl[i][1].first_s, ompl[i][1].limit.length);
  }

  auto ok = [](const PathSummary& s) { return s.found && s.checked; };
  nlohmann::json j;
  j["options"] = {{"clearance_m", clearance},     {"deadline_s", deadline},       {"ompl_time_s", ompl_time},
                  {"seeds", seeds},               {"instances", instances},       {"displacement_m", displacement},
                  {"ompl_seed", ompl_seed},       {"footprint", "3.3 x 10 m"},    {"turn_radius_m", options.turn_radius},
                  {"ompl_version", kOmplVersion}, {"ompl_planners", {"RRTstar", "BITstar"}}};
  std::printf("planner_ompl_bench: %d mines of 4 x 6 pillars, %zu requests; ours stopped at %.3g s, OMPL %s with the\n"
              "time ours took (\"budget\") and %.3g s; thread CPU ms; lengths in m driven (turns in place 0 m);\n"
              "medians over the paths found and accepted by the independent checker\n",
              seeds, n_requests, deadline, kOmplVersion.c_str(), ompl_time);
  std::printf("%-10s %-8s %3s %7s %7s %9s %9s %9s %8s %8s %6s %10s %10s\n", "scenario", "planner", "n", "found", "found",
              "first", "len", "len", "cost", "gap", "rev.", "to<=ours", "reached");
  std::printf("%-10s %-8s %3s %7s %7s %9s %9s %9s %8s %8s %6s %10s %10s\n", "", "", "", "budget", "1 s", "(ms)", "budget",
              "1 s", "1 s", "(mm)", "1 s", "(ms)", "");
  for (const std::string& scenario : bench::PlannerScenarioNames()) {
    std::vector<size_t> rows;
    for (size_t i = 0; i < n_requests; ++i)
      if (mine.requests[i].scenario == scenario) rows.push_back(i);
    const int n = static_cast<int>(rows.size());
    // Ours.
    {
      std::vector<double> ms, len, cost, rev;
      int found = 0;
      for (size_t i : rows) {
        if (!ok(ours[i].path)) continue;
        ++found;
        ms.push_back(1e3 * ours[i].s);
        len.push_back(ours[i].path.length);
        cost.push_back(ours[i].path.cost);
        rev.push_back(ours[i].path.reversals);
      }
      std::printf("%-10s %-8s %3d %7d %7s %9.2f %9.1f %9s %8.1f %8s %6.1f %10s %10s\n", scenario.c_str(), "ours", n, found,
                  "", MedianOf(ms), MedianOf(len), "", MedianOf(cost), "", MedianOf(rev), "", "");
      j["summary"][scenario]["ours"] = {{"requests", n},
                                        {"found", found},
                                        {"ms_median", Num(MedianOf(ms))},
                                        {"length_m_median", Num(MedianOf(len))},
                                        {"cost_median", Num(MedianOf(cost))},
                                        {"reversals_median", Num(MedianOf(rev))}};
    }
    for (size_t k = 0; k < 2; ++k) {
      std::vector<double> first, len_budget, len_limit, cost, rev, to_ours, gap;
      int found_budget = 0, found_limit = 0, ours_found = 0, reached = 0;
      for (size_t i : rows) {
        const OmplOutcome& m = ompl[i][k];
        if (ok(m.budget)) ++found_budget, len_budget.push_back(m.budget.length);
        if (ok(m.limit)) {
          ++found_limit;
          first.push_back(1e3 * m.first_s);
          len_limit.push_back(m.limit.length);
          cost.push_back(m.limit.cost);
          rev.push_back(m.limit.reversals);
          gap.push_back(1e3 * m.max_gap);
        }
        if (ok(ours[i].path)) {
          ++ours_found;
          if (std::isfinite(m.to_ours_s)) ++reached, to_ours.push_back(1e3 * m.to_ours_s);
        }
      }
      const std::string name = k == 0 ? "RRT*" : "BIT*";
      std::printf("%-10s %-8s %3d %7d %7d %9.2f %9.1f %9.1f %8.1f %8.4f %6.1f %10.1f %5d / %2d\n", "", name.c_str(), n,
                  found_budget, found_limit, MedianOf(first), MedianOf(len_budget), MedianOf(len_limit), MedianOf(cost),
                  bench::Max(gap), MedianOf(rev), MedianOf(to_ours), reached, ours_found);
      j["summary"][scenario][kOmplPlanners[k]] = {{"requests", n},
                                                  {"found_at_budget", found_budget},
                                                  {"found_at_ompl_time", found_limit},
                                                  {"first_ms_median", Num(MedianOf(first))},
                                                  {"length_m_median_at_budget", Num(MedianOf(len_budget))},
                                                  {"length_m_median_at_ompl_time", Num(MedianOf(len_limit))},
                                                  {"cost_median_at_ompl_time", Num(MedianOf(cost))},
                                                  {"reversals_median_at_ompl_time", Num(MedianOf(rev))},
                                                  {"conversion_gap_mm_max", bench::Max(gap)},
                                                  {"ms_to_ours_length_median", Num(MedianOf(to_ours))},
                                                  {"reached_ours_length", reached},
                                                  {"ours_found", ours_found}};
    }
  }

  // The targets, per request (OMPL = the better of its two planners).
  int ompl_only = 0, both = 0, ours_shorter_or_equal = 0, ours_found = 0, ten_times = 0;
  std::vector<double> length_ratio, speedup;
  for (size_t i = 0; i < n_requests; ++i) {
    const bool we = ok(ours[i].path);
    double ompl_len = kInf, ompl_to_ours = kInf, ompl_ran = 0.0;
    bool they = false;
    for (const OmplOutcome& m : ompl[i]) {
      if (ok(m.limit)) they = true, ompl_len = std::min(ompl_len, m.limit.length);
      ompl_to_ours = std::min(ompl_to_ours, m.to_ours_s);
      ompl_ran = std::max(ompl_ran, m.ran_s);
    }
    if (they && !we) ++ompl_only;
    if (they && we) {
      ++both;
      if (ours[i].path.length <= ompl_len + 1e-6) ++ours_shorter_or_equal;
      length_ratio.push_back(ours[i].path.length / ompl_len);
    }
    if (we) {
      ++ours_found;
      // Not reached in the run: at least the run's time (a lower bound on the ratio).
      const double t = std::isfinite(ompl_to_ours) ? ompl_to_ours : ompl_ran;
      const double ratio = t / std::max(ours[i].s, 1e-9);
      speedup.push_back(ratio);
      if (ratio >= 10.0) ++ten_times;
    }
    nlohmann::json row = {{"scenario", mine.requests[i].scenario},
                          {"index", i},
                          {"ours", {{"status", ours[i].status},
                                    {"ms", 1e3 * ours[i].s},
                                    {"found", ok(ours[i].path)},
                                    {"length_m", Num(ours[i].path.length)},
                                    {"cost", Num(ours[i].path.cost)},
                                    {"reversals", ours[i].path.reversals}}}};
    for (size_t k = 0; k < 2; ++k) {
      const OmplOutcome& m = ompl[i][k];
      row[kOmplPlanners[k]] = {{"ran_ms", 1e3 * m.ran_s},
                               {"budget_ms", 1e3 * m.budget_s},
                               {"first_ms", Num(1e3 * m.first_s)},
                               {"ms_to_ours_length", Num(1e3 * m.to_ours_s)},
                               {"improvements", m.trace.size()},
                               {"found_at_budget", ok(m.budget)},
                               {"length_m_at_budget", Num(m.budget.length)},
                               {"found_at_ompl_time", ok(m.limit)},
                               {"length_m_at_ompl_time", Num(m.limit.length)},
                               {"cost_at_ompl_time", Num(m.limit.cost)},
                               {"reversals_at_ompl_time", m.limit.reversals},
                               {"conversion_gap_m_max", m.max_gap}};
    }
    j["requests"].push_back(row);
  }
  std::printf("\nTargets (OMPL = the better of RRT* and BIT* within %.3g s):\n", ompl_time);
  std::printf("  success wherever OMPL succeeds: OMPL found a path where ours did not in %d of %zu requests  %s\n",
              ompl_only, n_requests, bench::Verdict(ompl_only == 0));
  std::printf("  shorter or equal paths: ours <= OMPL's in %d of %d requests both solved (median ours / OMPL %.3f)  %s\n",
              ours_shorter_or_equal, both, MedianOf(length_ratio), bench::Verdict(ours_shorter_or_equal == both));
  std::printf("  >= 10x less time to a path of equal length: %d of %d requests ours solved (median ratio %.1fx;\n"
              "    where OMPL never reached our length its whole run counts: a lower bound)  %s\n",
              ten_times, ours_found, MedianOf(speedup), bench::Verdict(ten_times == ours_found));
  j["targets"] = {{"ompl_found_ours_not", ompl_only},
                  {"both_found", both},
                  {"ours_shorter_or_equal", ours_shorter_or_equal},
                  {"length_ratio_ours_over_ompl_median", Num(MedianOf(length_ratio))},
                  {"ours_found", ours_found},
                  {"at_least_10x_faster_to_equal_length", ten_times},
                  {"time_ratio_ompl_over_ours_median_lower_bound", Num(MedianOf(speedup))}};
  bench::WriteJson(json_out, j);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::RunBenchMain("planner_ompl_bench", Run, argc, argv); }
