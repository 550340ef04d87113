// The path planner (planner/README.md, issue 13) on the synthetic room-and-pillar mine and the
// Moving AI grids.
//
// SE(2) section: a 4 x 6 pillar panel (12 m pillars, 6 m entries, walls jittered by the
// fractal midpoint displacement of sim/mine_generator.h), the default miner (3.3 x 10 m,
// turning radius 4 m), 0.1 m clearance. Faces close some entries between two crossings (a
// wall across the entry, as at a development heading). Scenarios, each on every seed's mine:
//   box_cut    from 10-18 m back in the entry up to the face (nose 0.6 m from it), the face
//              a wall across the entry 1 m before the next crossing (an 11 m dead end);
//   slab_cut   at the face, shifted sideways across the entry (one side to the other);
//   back_out   from the face backwards round the corner into the crosscut behind;
//   turn       from an entry 12 m before a crossing into the crosscut, 12 m past it;
//   long_entry along a whole entry (101 m), lateral offset and heading changed at the ends;
//   long       across the section, corner to corner (> 100 m straight-line distance).
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
#include <random>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"
#include "planner/se2_planner.h"
#include "planner/testing/path_checker.h"
#include "sim/mine_generator.h"

namespace {

using minenav::kPi;
using minenav::Pose2;
using minenav::Se2Planner;
using minenav::Se2PlanResult;
using minenav::Segment;
namespace bench = minenav::bench;

constexpr double kPillar = 12.0;
// The entries' width (--room_width, default 6 m) and the pillar pitch.
double room = 6.0, pitch = kPillar + room;
constexpr double kBytesPerState = 80.0;  // search_limits.h: about 80 bytes per stored SE(2) state

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(at)), hi = std::min(v.size() - 1, lo + 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

struct Request {
  std::string scenario;
  const Se2Planner* planner = nullptr;
  Pose2 start, goal;
};

struct Outcome {
  bool found = false, checked = false;
  double cold_s = 0.0, warm_s = 0.0, length = 0.0;
  int64_t expansions = 0, states = 0;
  int reversals = 0;
  std::string status;
};

// Entry k (0 = south boundary entry) centre line y; crosscut c centre line x.
double EntryY(int k) { return 0.5 * room + k * pitch; }
double CrosscutX(int c) { return 0.5 * room + c * pitch; }
// A face across an entry 1 m before the crossing east of pillar column c: a dead end 11 m long.
double FaceX(int c) { return room + c * pitch + kPillar - 1.0; }

// The first free pose from `p` moving by `step` (at most `tries` times); p itself if none.
Pose2 NudgeFree(const Se2Planner& planner, Pose2 p, const Eigen::Vector2d& step, int tries) {
  for (int i = 0; i < tries && !planner.PoseFree(p); ++i) {
    p.x += step.x();
    p.y += step.y();
  }
  return p;
}

int Run(int argc, char** argv) {
  int seeds = 3, instances = 4;
  double deadline = 10.0, displacement = 0.1, clearance = 0.05;
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
  pitch = kPillar + room;

  const minenav::Footprint miner = minenav::Footprint::Rectangle(3.3, 10.0);
  options.clearance = clearance;
  options.shot_heuristic = shot_heuristic;
  minenav::SearchLimits limits;
  limits.max_expansions = 1'000'000;
  double stop_at = 0.0;
  limits.stop_requested = [&stop_at] { return bench::Now() > stop_at; };

  std::vector<std::unique_ptr<Se2Planner>> planners;
  std::vector<std::vector<Segment>> maps;
  std::vector<Request> requests;
  std::vector<double> setup_s;
  for (int seed = 1; seed <= seeds; ++seed) {
    minenav::MineOptions mine;
    mine.pillar_rows = 4;
    mine.pillar_cols = 6;
    mine.pillar_size = kPillar;
    mine.room_width = room;
    mine.midpoint_displacement = displacement;
    mine.seed = static_cast<uint64_t>(seed);
    const std::vector<Segment> plain = minenav::GenerateRoomAndPillarMine(mine);
    const Eigen::Vector2d size = minenav::MinePanelSize(mine);
    std::mt19937 rng(static_cast<unsigned>(seed));
    // Faces: across entry k beside pillar column c (entries 0..3, so the crosscut behind the
    // dead end has a north arm to back into).
    std::vector<std::pair<int, int>> faces;
    for (int i = 0; i < instances; ++i) faces.push_back({i % 4, 1 + static_cast<int>(rng() % 5)});
    std::vector<Segment> with_faces = plain;
    for (const auto& [k, c] : faces) {
      const double xf = FaceX(c);
      with_faces.push_back({xf, k * pitch - 1.0, xf, k * pitch + room + 1.0});
    }
    for (const std::vector<Segment>* m : {&plain, static_cast<const std::vector<Segment>*>(&with_faces)}) {
      const double t0 = bench::Now();
      planners.push_back(std::make_unique<Se2Planner>(*m, miner, options));
      setup_s.push_back(bench::Now() - t0);
      maps.push_back(*m);
      if (!planners.back()->setup_error().empty())
        throw std::runtime_error("planner setup: " + planners.back()->setup_error());
    }
    const Se2Planner& open = *planners[planners.size() - 2];
    const Se2Planner& faced = *planners.back();
    std::uniform_real_distribution<double> back(10.0, 18.0), lateral(-0.4, 0.4), yaw(-0.08, 0.08);
    for (const auto& [k, c] : faces) {
      const double xf = FaceX(c), y = EntryY(k);
      const Eigen::Vector2d away(-0.1, 0.0);
      const Pose2 at_face = NudgeFree(faced, Pose2(xf - 5.6, y, 0.0), away, 20);
      const double shift = 0.7;
      const Pose2 left = NudgeFree(faced, Pose2(xf - 5.6, y + shift, 0.0), away, 20);
      const Pose2 right = NudgeFree(faced, Pose2(xf - 5.6, y - shift, 0.0), away, 20);
      const Pose2 behind(std::max(5.5, at_face.x - back(rng)), y + lateral(rng), yaw(rng));
      requests.push_back({"box_cut", &faced, behind, at_face});
      requests.push_back({"slab_cut", &faced, left, right});
      // Backing out: rear first round the corner into the north arm of the crosscut behind.
      requests.push_back({"back_out", &faced, at_face, Pose2(CrosscutX(c), y + 12.0, -kPi / 2)});
    }
    // Turns from an entry into a crosscut at inner crossings, left or right.
    for (int i = 0; i < instances; ++i) {
      const int k = 1 + i % 3, c = 1 + static_cast<int>(rng() % 5);
      const double side = i % 2 == 0 ? 1.0 : -1.0;
      requests.push_back({"turn", &open, Pose2(CrosscutX(c) - 12.0, EntryY(k) + lateral(rng), yaw(rng)),
                          Pose2(CrosscutX(c), EntryY(k) + side * 12.0, side * kPi / 2)});
    }
    // Along a whole entry, > 100 m, with a lateral offset and a heading change at the ends.
    for (int i = 0; i < instances; ++i) {
      const int k = i % 5;
      requests.push_back({"long_entry", &open, Pose2(6.5, EntryY(k) + lateral(rng), yaw(rng)),
                          Pose2(size.x() - 6.5, EntryY(k) + lateral(rng), yaw(rng))});
    }
    // Across the section, corner to corner.
    for (int i = 0; i < instances; ++i) {
      const bool flip = i % 2 == 1;
      const Pose2 a(10.0 + lateral(rng), EntryY(0) + lateral(rng), 0.0);
      const Pose2 b(size.x() - 10.0 + lateral(rng), EntryY(4) + lateral(rng), i % 4 < 2 ? 0.0 : kPi);
      requests.push_back({"long", &open, flip ? b : a, flip ? a : b});
    }
  }

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
  std::printf("%-10s %4s %6s %9s %9s %9s %9s %9s %8s %6s %9s %7s\n", "scenario", "n", "found", "cold med", "cold p95",
              "cold max", "warm med", "expans.", "length", "rev.", "states", "MB");
  std::printf("%-10s %4s %6s %9s %9s %9s %9s %9s %8s %6s %9s %7s\n", "", "", "", "(ms)", "(ms)", "(ms)", "(ms)", "(med)",
              "(m,med)", "(med)", "(max)", "(max)");
  for (const std::string name : {"box_cut", "slab_cut", "back_out", "turn", "long_entry", "long"}) {
    std::vector<double> cold, warm, expansions, length, reversals;
    double states = 0.0;
    int n = 0, ok = 0;
    if (!only.empty() && ("," + only + ",").find("," + name + ",") == std::string::npos) continue;
    for (size_t i = 0; i < requests.size(); ++i) {
      if (requests[i].scenario != name) continue;
      const Outcome& o = outcomes[i];
      ++n;
      cold.push_back(1e3 * o.cold_s);
      if (o.found) warm.push_back(1e3 * o.warm_s);
      expansions.push_back(static_cast<double>(o.expansions));
      states = std::max(states, static_cast<double>(o.states));
      if (!(o.found && o.checked)) continue;
      ++ok;
      length.push_back(o.length);
      reversals.push_back(o.reversals);
    }
    const double mb = states * kBytesPerState / 1e6;
    std::printf("%-10s %4d %6d %9.2f %9.2f %9.2f %9.2f %9.0f %8.1f %6.1f %9.0f %7.1f\n", name.c_str(), n, ok,
                bench::Median(cold), Percentile(cold, 0.95), bench::Max(cold), bench::Median(warm),
                bench::Median(expansions), bench::Median(length), bench::Median(reversals), states, mb);
    j["se2"][name] = {{"requests", n},
                      {"success", ok},
                      {"cold_ms_median", bench::Median(cold)},
                      {"cold_ms_p95", Percentile(cold, 0.95)},
                      {"cold_ms_max", bench::Max(cold)},
                      {"warm_ms_median", bench::Median(warm)},
                      {"warm_ms_p95", Percentile(warm, 0.95)},
                      {"expansions_median", bench::Median(expansions)},
                      {"length_m_median", bench::Median(length)},
                      {"reversals_median", bench::Median(reversals)},
                      {"states_max", states},
                      {"memory_mb_max_estimate", mb}};
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
