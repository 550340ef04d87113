// Ladar scan simulation speed: a 2048-point scan of a large synthetic room-and-pillar mine
// (thesis 5.2.1), ray-cast through the segment index (common/segment_index.h) and by
// brute force (common/geometry.h CastRay), side by side, plus the full Typhoon model
// (noise, quantisation, mixed pixels) and a whole 42-station survey.
//
//   ladar_sim_bench [--rows 8] [--cols 10] [--stations 42] [--points 2048] [--repeat 3]
//                   [--json-out FILE]
// Prints a table; medians over stations x repeats.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/segment_index.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/mine_generator.h"

namespace {

using minenav::Pose2;

double Seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int Run(int argc, char** argv) {
  int rows = 8, cols = 10, stations = 42, points = 2048, repeat = 3;
  std::string json_out;
  minenav::ConfigSchema schema("ladar_sim_bench",
                               "Time per simulated ladar scan on a large synthetic mine: grid vs brute force.");
  schema.AddInt("rows", &rows, "pillar rows of the synthetic mine", 1, 100);
  schema.AddInt("cols", &cols, "pillar columns of the synthetic mine", 1, 100);
  schema.AddInt("stations", &stations, "survey stations (scans per repeat)", 1, 10000);
  schema.AddInt("points", &points, "readings per scan", 1, 100000);
  schema.AddInt("repeat", &repeat, "times the survey is repeated", 1, 100);
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  minenav::MineOptions mine;
  mine.pillar_rows = rows;
  mine.pillar_cols = cols;
  const std::vector<minenav::Segment> world = minenav::GenerateRoomAndPillarMine(mine);
  const std::vector<minenav::Station> survey = minenav::MineSurveyStations(mine, stations);

  double t0 = Seconds();
  const minenav::StaticSegmentIndex grid(world);
  const double build_s = Seconds() - t0;

  minenav::LadarModel ideal = minenav::LadarModel::Typhoon().Ideal();
  ideal.num_points = points;
  ideal.angular_resolution = 0.0;
  minenav::LadarModel typhoon = minenav::LadarModel::Typhoon();
  typhoon.num_points = points;
  typhoon.angular_resolution = 0.0;
  const double step = ideal.AngleStep();

  std::vector<double> grid_s, brute_s, typhoon_s;
  long mismatches = 0, hits = 0;
  const minenav::LadarSimulator sim(typhoon, 1);
  double survey_total = 0.0;
  for (int r = 0; r < repeat; ++r) {
    double survey_start = Seconds();
    for (size_t k = 0; k < survey.size(); ++k) {
      t0 = Seconds();
      const minenav::LadarScan scan = sim.Simulate(grid, survey[k].pose, Pose2(), 0, static_cast<int64_t>(k));
      typhoon_s.push_back(Seconds() - t0);
      if (scan.ranges.size() != static_cast<size_t>(points)) return minenav::kExitRuntime;
    }
    survey_total += Seconds() - survey_start;
    for (const minenav::Station& st : survey) {
      const Eigen::Vector2d o = st.pose.translation();
      std::vector<minenav::RayHit> fast(static_cast<size_t>(points)), slow(static_cast<size_t>(points));
      t0 = Seconds();
      for (int i = 0; i < points; ++i) {
        const auto h = grid.CastRay(o, st.pose.theta + i * step, ideal.max_range);
        fast[static_cast<size_t>(i)] = h ? *h : minenav::RayHit{};
      }
      grid_s.push_back(Seconds() - t0);
      t0 = Seconds();
      for (int i = 0; i < points; ++i) {
        const auto h = minenav::CastRay(o, st.pose.theta + i * step, world, ideal.max_range);
        slow[static_cast<size_t>(i)] = h ? *h : minenav::RayHit{};
      }
      brute_s.push_back(Seconds() - t0);
      for (int i = 0; i < points; ++i) {
        const auto& a = fast[static_cast<size_t>(i)];
        const auto& b = slow[static_cast<size_t>(i)];
        hits += a.segment >= 0;
        mismatches += a.segment != b.segment || a.range != b.range;
      }
    }
  }
  const double grid_ms = 1e3 * Median(grid_s), brute_ms = 1e3 * Median(brute_s), typhoon_ms = 1e3 * Median(typhoon_s);
  const double survey_s = survey_total / repeat;

  std::printf("ladar_sim_bench: synthetic mine %d x %d pillars, %zu segments, grid %d x %d cells of %.2f m (%zu entries)\n",
              rows, cols, world.size(), grid.cols(), grid.rows(), grid.cell_size(), grid.entries());
  std::printf("%-44s %12s\n", "measure (median over stations x repeats)", "value");
  std::printf("%-44s %12.3f\n", "grid build (ms)", 1e3 * build_s);
  std::printf("%-44s %12.3f\n", "ray casting, grid (ms per scan)", grid_ms);
  std::printf("%-44s %12.3f\n", "ray casting, brute force (ms per scan)", brute_ms);
  std::printf("%-44s %12.1f\n", "speed-up (brute / grid)", brute_ms / grid_ms);
  std::printf("%-44s %12.3f\n", "full Typhoon model, grid (ms per scan)", typhoon_ms);
  std::printf("%-44s %12.3f\n", "whole survey, Typhoon model (s)", survey_s);
  std::printf("%-44s %12ld\n", "grid vs brute force mismatches", mismatches);
  std::printf("(%d stations x %d points, %d repeats, %ld rays hit)\n", stations, points, repeat, hits);

  if (!json_out.empty()) {
    nlohmann::json j;
    j["benchmark"] = "ladar_sim_bench";
    j["mine"] = {{"pillar_rows", rows}, {"pillar_cols", cols}, {"segments", world.size()}};
    j["grid"] = {{"cols", grid.cols()}, {"rows", grid.rows()}, {"cell_size_m", grid.cell_size()},
                 {"entries", grid.entries()}, {"build_ms", 1e3 * build_s}};
    j["stations"] = stations;
    j["points"] = points;
    j["repeat"] = repeat;
    j["median_ms_per_scan"] = {{"grid", grid_ms}, {"brute_force", brute_ms}, {"typhoon_full_model", typhoon_ms}};
    j["speedup"] = brute_ms / grid_ms;
    j["survey_s"] = survey_s;
    j["mismatches"] = mismatches;
    minenav::WriteFileAtomically(json_out, j.dump(2) + "\n");
  }
  return mismatches == 0 ? 0 : minenav::kExitRuntime;
}

}  // namespace

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("ladar_sim_bench", Run, argc, argv); }
