// The path planner (planner/README.md, issue 13) on the synthetic room-and-pillar mine and the
// Moving AI grids.
//
// SE(2) section: the scenarios of bench/planner_scenarios.h (box_cut, slab_cut, back_out, turn,
// long_entry, long on mines of 4 x 6 pillars), the default miner (3.3 x 10 m, turning radius
// 4 m).
// Each request is planned twice: "cold" (the first request to that goal) and "warm" (the same
// request again: what the planner keeps between requests to one goal). Times are thread CPU
// seconds (bench_util.h). Every path is checked by the independent checker
// (planner/testing/path_checker.h); a path it rejects counts as a failure.
//
// Grid section: every scenario of each Moving AI map in MINENAV_DATASETS_DIR/movingai, time
// and expansions per bucket, and how many lengths equal the published optimum within 1e-3.
//
//   planner_bench [--seeds 3] [--instances 4] [--deadline 10] [--grid true] [--json_out FILE]
//                 [--room_width 6] [--only box_cut,turn] [--planner.xy-resolution 0.1 ...]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "bench/planner_scenarios.h"
#include "common/config.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"
#include "planner/se2_planner.h"
#include "planner/testing/path_checker.h"

namespace {

using minenav::kPi;
using minenav::Pose2;
using minenav::Se2Planner;
using minenav::Se2PlanResult;
using minenav::Segment;
namespace bench = minenav::bench;

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at)), hi = std::min(v.size() - 1, lo + 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

using Request = bench::PlannerRequest;

struct Outcome {
  bool found = false, checked = false;
  double cold_s = 0.0, warm_s = 0.0, length = 0.0;
  int64_t expansions = 0, states = 0, memory_bytes = 0;
  int64_t pose_checks = 0, exact_tests = 0;  // poses checked for collision; of them, by the exact test
  int reversals = 0;
  std::string status;
};

int Run(int argc, char** argv) {
  int seeds = 3, instances = 4;
  double deadline = 10.0, displacement = 0.1, clearance = 0.05, room = 6.0;
  bool grid = true, shot_heuristic = true;
  std::string json_out, only;
  minenav::Se2PlannerOptions options;
  minenav::ConfigSchema schema("planner_bench", "SE(2) planner on the synthetic mine's maneuvers and the grid search on Moving AI.");
  schema.AddInt("seeds", &seeds, "synthetic mines (seeds 1..n)", 1, 100);
  schema.AddInt("instances", &instances, "requests per scenario and mine", 1, 100);
  schema.AddDouble("deadline", &deadline, "s", "CPU time after which one SE(2) request is stopped", 0.01, 1000.0);
  schema.AddDouble("displacement", &displacement, "m", "the mine walls' fractal midpoint displacement (sim/mine_generator.h)", 0.0, 1.0);
  schema.AddDouble("clearance", &clearance, "m", "the planner's clearance", 0.0, 1.0);
  schema.AddBool("shot_heuristic", &shot_heuristic, "the planner's shot_heuristic option");
  schema.AddBool("grid", &grid, "run the Moving AI section");
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  schema.AddDouble("room_width", &room, "m",
                   "the entries' and crosscuts' width (6 m: a miner turning at a crossing has 0.077 m at 45 deg, "
                   "planner_test)",
                   4.0, 20.0);
  schema.AddString("only", &only, "plan only the scenarios whose names are in this comma list ('' = all)");
  minenav::DeclareOptions(minenav::OptionScope(schema).Nested("planner"), options);  // planner.clearance and planner.shot_heuristic: see --clearance, --shot_heuristic
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  const minenav::Footprint miner = minenav::Footprint::Rectangle(3.3, 10.0);
  options.clearance = clearance;
  options.shot_heuristic = shot_heuristic;
  minenav::SearchLimits limits;
  limits.max_expansions = 1'000'000;
  double stop_at = 0.0;
  limits.stop_requested = [&stop_at] { return bench::Now() > stop_at; };

  bench::PlannerScenarios mine = bench::BuildPlannerScenarios(seeds, instances, displacement, miner, options, room);
  const std::vector<std::unique_ptr<Se2Planner>>& planners = mine.planners;
  const std::vector<std::vector<Segment>>& maps = mine.maps;
  const std::vector<Request>& requests = mine.requests;
  const std::vector<double>& setup_s = mine.setup_s;

  // Plan every request cold, then all again warm (same goal, same request).
  std::vector<Outcome> outcomes(requests.size());
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < requests.size(); ++i) {
      const Request& q = requests[i];
      Outcome& o = outcomes[i];
      if (pass == 1 && !o.found) continue;  // warm times only where the cold request found a path
      if (!only.empty() && ("," + only + ",").find("," + q.scenario + ",") == std::string::npos) continue;
      const double t0 = bench::Now();
      stop_at = t0 + deadline;
      const Se2PlanResult r = q.planner->Plan(q.start, q.goal, limits);
      const double t = bench::Now() - t0;
      if (pass == 1) {
        o.warm_s = t;
        continue;
      }
      o.cold_s = t;
      o.status = minenav::ToString(r.status);
      o.found = r.status == minenav::SearchStatus::kFound;
      o.expansions = r.expansions;
      o.states = r.states;
      o.memory_bytes = r.memory_bytes;
      o.pose_checks = r.collisions.free_by_field + r.collisions.blocked_by_field + r.collisions.exact_tests;
      o.exact_tests = r.collisions.exact_tests;
      if (!o.found) {
        std::fprintf(stderr, "%s %zu: %s\n", q.scenario.c_str(), i, r.reason.c_str());
        continue;
      }
      o.length = r.path.Length();
      o.reversals = r.path.Reversals();
      minenav::testing::PathCheckSettings st;
      st.polygon = q.planner->footprint().vertices;
      st.turn_radius = q.planner->options().turn_radius;
      st.clearance = q.planner->options().clearance;
      st.sample_step = 0.02;
      std::vector<minenav::testing::CheckedPiece> pieces;
      for (const auto& p : r.path.pieces) pieces.push_back({static_cast<int>(p.motion), p.end});
      const size_t map_index = static_cast<size_t>(
          std::find_if(planners.begin(), planners.end(), [&](const auto& p) { return p.get() == q.planner; }) -
          planners.begin());
      const auto report = minenav::testing::CheckPath(maps[map_index], q.start, pieces, st);
      o.checked = report.ok;
      if (!report.ok) std::fprintf(stderr, "%s %zu: checker: %s\n", q.scenario.c_str(), i, report.problem.c_str());
    }

  nlohmann::json j;
  j["options"] = {{"clearance_m", options.clearance}, {"deadline_s", deadline}, {"seeds", seeds},
                  {"instances", instances}, {"footprint", "3.3 x 10 m"}, {"turn_radius_m", options.turn_radius}};
  j["setup_s_median"] = bench::Median(setup_s);
  std::printf("planner_bench: %d mines of 4 x 6 pillars, %zu SE(2) requests, planner setup median %.3f s\n", seeds,
              requests.size(), bench::Median(setup_s));
  std::printf("%-10s %4s %6s %9s %9s %9s %9s %9s %8s %6s %9s %7s %9s %7s\n", "scenario", "n", "found", "cold med",
              "cold p95", "cold max", "warm med", "expans.", "length", "rev.", "states", "MB", "checks", "exact");
  std::printf("%-10s %4s %6s %9s %9s %9s %9s %9s %8s %6s %9s %7s %9s %7s\n", "", "", "", "(ms)", "(ms)", "(ms)", "(ms)",
              "(med)", "(m,med)", "(med)", "(max)", "(max)", "(med)", "(%,med)");
  for (const std::string name : {"box_cut", "slab_cut", "back_out", "turn", "long_entry", "long"}) {
    std::vector<double> cold, warm, expansions, length, reversals, checks, exact_share;
    double states = 0.0, bytes = 0.0;
    int n = 0, ok = 0;
    if (!only.empty() && ("," + only + ",").find("," + name + ",") == std::string::npos) continue;
    for (size_t i = 0; i < requests.size(); ++i) {
      if (requests[i].scenario != name) continue;
      const Outcome& o = outcomes[i];
      ++n;
      cold.push_back(1e3 * o.cold_s);
      if (o.found) warm.push_back(1e3 * o.warm_s);
      expansions.push_back(static_cast<double>(o.expansions));
      checks.push_back(static_cast<double>(o.pose_checks));
      if (o.pose_checks > 0) exact_share.push_back(100.0 * static_cast<double>(o.exact_tests) / static_cast<double>(o.pose_checks));
      states = std::max(states, static_cast<double>(o.states));
      bytes = std::max(bytes, static_cast<double>(o.memory_bytes));
      if (!(o.found && o.checked)) continue;
      ++ok;
      length.push_back(o.length);
      reversals.push_back(o.reversals);
    }
    const double mb = bytes / 1e6;  // the search's storage (Se2PlanResult::memory_bytes), largest request
    std::printf("%-10s %4d %6d %9.2f %9.2f %9.2f %9.2f %9.0f %8.1f %6.1f %9.0f %7.1f %9.0f %7.1f\n", name.c_str(), n, ok,
                bench::Median(cold), Percentile(cold, 0.95), bench::Max(cold), bench::Median(warm),
                bench::Median(expansions), bench::Median(length), bench::Median(reversals), states, mb,
                bench::Median(checks), bench::Median(exact_share));
    j["se2"][name] = {{"requests", n},
                      {"success", ok},
                      {"cold_ms_median", bench::Median(cold)},
                      {"cold_ms_p95", Percentile(cold, 0.95)},
                      {"cold_ms_max", bench::Max(cold)},
                      {"warm_ms_median", bench::Median(warm)},
                      {"warm_ms_p95", Percentile(warm, 0.95)},
                      {"expansions_median", bench::Median(expansions)},
                      {"pose_checks_median", bench::Median(checks)},
                      {"exact_test_percent_median", bench::Median(exact_share)},
                      {"length_m_median", bench::Median(length)},
                      {"reversals_median", bench::Median(reversals)},
                      {"states_max", states},
                      {"memory_mb_max", mb}};
  }

  if (grid) {
    const std::string dir = std::string(MINENAV_DATASETS_DIR) + "/movingai";
    std::printf("\ngrid: Moving AI, every scenario (%s)\n", dir.c_str());
    std::printf("%-22s %9s %9s %9s %10s %10s %12s\n", "map", "scenarios", "optimal", "buckets", "total (s)",
                "med (ms)", "expans.(med)");
    for (const std::string name :
         {"dao/arena.map", "dao/den312d.map", "dao/lak303d.map", "room/8room_000.map", "room/32room_000.map"}) {
      const std::string path = dir + "/" + name;
      if (!std::filesystem::exists(path)) throw std::runtime_error("missing " + path);
      const minenav::OccupancyGrid g = minenav::LoadMovingAiMap(path);
      const auto scenarios = minenav::LoadMovingAiScenarios(path + ".scen");
      minenav::CheckScenariosFitMap(scenarios, g, path + ".scen");
      minenav::GridAStar astar(g);
      std::map<int, std::vector<double>> bucket_ms, bucket_expansions;
      std::vector<double> all_ms, all_expansions;
      int optimal = 0;
      double total = 0.0;
      for (const auto& s : scenarios) {
        const double t0 = bench::Now();
        const minenav::GridSearchResult r = astar.Plan(s.start, s.goal);
        const double t = bench::Now() - t0;
        total += t;
        if (r.status == minenav::SearchStatus::kFound && std::abs(r.length - s.optimal_length) <= 1e-3) ++optimal;
        bucket_ms[s.bucket].push_back(1e3 * t);
        bucket_expansions[s.bucket].push_back(static_cast<double>(r.expansions));
        all_ms.push_back(1e3 * t);
        all_expansions.push_back(static_cast<double>(r.expansions));
      }
      std::printf("%-22s %9zu %9d %9zu %10.3f %10.4f %12.0f\n", name.c_str(), scenarios.size(), optimal,
                  bucket_ms.size(), total, bench::Median(all_ms), bench::Median(all_expansions));
      nlohmann::json m = {{"scenarios", scenarios.size()}, {"optimal_within_1e-3", optimal}, {"total_s", total}};
      for (const auto& [b, ms] : bucket_ms)
        m["buckets"].push_back({{"bucket", b},
                                {"scenarios", ms.size()},
                                {"ms_median", bench::Median(ms)},
                                {"ms_max", bench::Max(ms)},
                                {"expansions_median", bench::Median(bucket_expansions[b])}});
      j["grid"][name] = m;
    }
  }
  bench::WriteJson(json_out, j);
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return bench::RunBenchMain("planner_bench", Run, argc, argv); }
