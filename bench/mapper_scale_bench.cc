// Contour mapper at scale: a research-mine-like area (thesis 5.3: narrow 3-4 m entries,
// irregular pillars, crib blocks and posts) surveyed with many stations, initial poses =
// truth + noise (σ 0.33 m, 3.33°). Reports how insert time and memory grow with the map,
// and the final accuracy (by default without a final refinement: the incremental cycle).
//
//   mapper_scale_bench [--seed 1] [--rows 4] [--cols 6] [--stations 110] [--refine_rounds 0]
//                      [--svg_out FILE] [--json_out FILE]

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/segment_index.h"
#include "mapper/contour_mapper.h"
#include "evaluation/map_evaluation.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/mine_generator.h"

namespace {

using minenav::Pose2;
namespace mapper = minenav::mapper;

// Resident set size of this process in MiB (Linux /proc), 0 if unknown.
double RssMiB() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      double kb = 0;
      in >> kb;
      return kb / 1024.0;
    }
    std::getline(in, key);
  }
  return 0.0;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

int Run(int argc, char** argv) {
  int seed = 1, rows = 4, cols = 6, stations = 110, refine_rounds = 0;
  std::string json_out, svg_out;
  bool remove_redundant = true;
  minenav::ConfigSchema schema("mapper_scale_bench", "Contour mapper on a large research-mine-like area.");
  schema.AddInt("seed", &seed, "seed of the mine, the scans and the initial-pose noise", 0, 1000000);
  schema.AddInt("rows", &rows, "pillar rows", 1, 50);
  schema.AddInt("cols", &cols, "pillar columns", 1, 50);
  schema.AddInt("stations", &stations, "survey stations", 2, 5000);
  schema.AddInt("refine_rounds", &refine_rounds, "final concurrent refinement rounds (0 = none)", 0, 1000);
  schema.AddBool("remove_redundant", &remove_redundant, "remove redundant contours in the final refinement");
  schema.AddString("svg_out", &svg_out, "write a 16 m window around the worst map deviation as SVG ('' = none)");
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  minenav::ResearchMineOptions mine;
  mine.pillar_rows = rows;
  mine.pillar_cols = cols;
  mine.seed = static_cast<uint64_t>(seed);
  const std::vector<minenav::Segment> world = minenav::GenerateResearchMine(mine);
  const std::vector<minenav::Station> survey = minenav::ResearchMineStations(mine, stations);
  const minenav::StaticSegmentIndex grid(world);
  const minenav::LadarSimulator sim(minenav::LadarModel::Typhoon(), static_cast<uint64_t>(seed));
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> nxy(0.0, 0.33), nth(0.0, minenav::DegToRad(3.33));

  mapper::ContourMapperOptions options;
  options.refinement.max_rounds = std::max(1, refine_rounds);
  options.refinement.remove_redundant = remove_redundant;
  mapper::ContourMapper cm(options);
  std::vector<Pose2> truth;
  std::vector<double> cpu;
  nlohmann::json growth = nlohmann::json::array();
  int refused = 0;
  double max_err = 0.0, max_h = 0.0;
  const double rss0 = RssMiB();
  const std::clock_t start = std::clock();
  std::printf("%8s %10s %10s %12s %14s %10s\n", "scans", "contours", "segments", "length (m)", "insert CPU (s)", "RSS (MiB)");
  for (size_t k = 0; k < survey.size(); ++k) {
    const Pose2 t = survey[k].pose;
    const Pose2 initial = k == 0 ? t : Pose2(t.x + nxy(rng), t.y + nxy(rng), t.theta + nth(rng));
    const minenav::LadarScan scan = sim.Simulate(grid, t, Pose2(), static_cast<int64_t>(k) * 100000, static_cast<int64_t>(k));
    const std::clock_t c0 = std::clock();
    const mapper::InsertResult r = cm.InsertScan(scan, initial);
    cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    if (!r.accepted) {
      ++refused;
      std::fprintf(stderr, "scan %zu refused: %s\n", k, r.reason.c_str());
    } else {
      std::fprintf(stderr, "scan %3zu: error %.4f m %.3f deg (%s)\n", k, minenav::TranslationDistance(r.pose, t),
                   minenav::RadToDeg(minenav::HeadingDistance(r.pose, t)), r.reason.c_str());
      max_err = std::max(max_err, minenav::TranslationDistance(r.pose, t));
      max_h = std::max(max_h, minenav::HeadingDistance(r.pose, t));
      truth.push_back(t);
    }
    if ((k + 1) % 10 == 0 || k + 1 == survey.size()) {
      const std::vector<double> last(cpu.end() - std::min<std::ptrdiff_t>(10, static_cast<std::ptrdiff_t>(cpu.size())), cpu.end());
      const double rss = RssMiB();
      std::printf("%8zu %10d %10d %12.1f %14.3f %10.1f\n", k + 1, cm.map().NumContours(), cm.map().NumSegments(),
                  cm.map().TotalLength(), Median(last), rss);
      growth.push_back({{"scans", k + 1}, {"contours", cm.map().NumContours()}, {"segments", cm.map().NumSegments()},
                        {"length_m", cm.map().TotalLength()}, {"median_insert_cpu_s_last10", Median(last)},
                        {"rss_mib", rss}});
    }
  }
  const double total = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
  double refine_cpu = 0.0;
  if (refine_rounds > 0) {
    const std::clock_t r0 = std::clock();
    const mapper::ConcurrentRefinementResult rr = cm.Refine();
    refine_cpu = static_cast<double>(std::clock() - r0) / CLOCKS_PER_SEC;
    max_err = max_h = 0.0;
    for (size_t k = 0; k < cm.scans().size(); ++k) {
      max_err = std::max(max_err, minenav::TranslationDistance(cm.scans()[k].pose, truth[k]));
      max_h = std::max(max_h, minenav::HeadingDistance(cm.scans()[k].pose, truth[k]));
    }
    std::printf("final refinement: %d rounds (%s), %.1f s CPU\npose graph: %s\n", rr.rounds, rr.reason.c_str(),
                refine_cpu, rr.loop_closure.reason.c_str());
  }
  const mapper::MapDeviation dev = mapper::ContourDeviation(cm.map(), world);
  std::printf("research mine %d x %d pillars, %zu wall segments, %d stations: %d refused, max pose error %.4f m %.3f deg,\n"
              "deviation mean %.4f m max %.4f m, total insert CPU %.1f s, RSS growth %.1f MiB\n",
              rows, cols, world.size(), stations, refused, max_err, minenav::RadToDeg(max_h), dev.mean, dev.max, total,
              RssMiB() - rss0);
  std::printf("worst deviation at (%.2f, %.2f) on contour %d\n", dev.worst_point.x(), dev.worst_point.y(), dev.worst_contour);
  if (!svg_out.empty()) {
    // True walls grey, contours blue (the worst one red), scan stations green, window 16 m.
    const Eigen::Vector2d c = dev.worst_point;
    const double half = 8.0, scale = 50.0;  // px per m
    auto px = [&](const Eigen::Vector2d& p) {
      return Eigen::Vector2d((p.x() - c.x() + half) * scale, (c.y() + half - p.y()) * scale);
    };
    std::string svg = "<svg xmlns='http://www.w3.org/2000/svg' width='800' height='800'>\n<rect width='800' height='800' fill='white'/>\n";
    char buf[256];
    for (const minenav::Segment& w : world) {
      const Eigen::Vector2d a = px(w.a), b = px(w.b);
      std::snprintf(buf, sizeof(buf), "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#999' stroke-width='6'/>\n", a.x(), a.y(), b.x(), b.y());
      svg += buf;
    }
    for (const auto& [id, contour] : cm.map().contours()) {
      const char* colour = id == dev.worst_contour ? "red" : "blue";
      for (int k = 0; k < contour.NumSegments(); ++k) {
        const minenav::Segment s = contour.GetSegment(k);
        const Eigen::Vector2d a = px(s.a), b = px(s.b);
        std::snprintf(buf, sizeof(buf), "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='%s' stroke-width='1.5'/>\n", a.x(), a.y(), b.x(), b.y(), colour);
        svg += buf;
      }
    }
    for (const mapper::MappedScan& m : cm.scans()) {
      const Eigen::Vector2d p = px(m.pose.translation());
      std::snprintf(buf, sizeof(buf), "<circle cx='%.1f' cy='%.1f' r='5' fill='green'/>\n", p.x(), p.y());
      svg += buf;
    }
    const Eigen::Vector2d w = px(c);
    std::snprintf(buf, sizeof(buf), "<circle cx='%.1f' cy='%.1f' r='12' fill='none' stroke='orange' stroke-width='2'/>\n", w.x(), w.y());
    svg += buf;
    svg += "</svg>\n";
    minenav::WriteFileAtomically(svg_out, svg);
  }
  if (!json_out.empty()) {
    nlohmann::json j;
    j["benchmark"] = "mapper_scale_bench";
    j["seed"] = seed;
    j["pillars"] = {rows, cols};
    j["wall_segments"] = world.size();
    j["stations"] = stations;
    j["refused"] = refused;
    j["max_pose_error_m"] = max_err;
    j["max_heading_error_deg"] = minenav::RadToDeg(max_h);
    j["map_deviation"] = {{"mean_m", dev.mean}, {"max_m", dev.max}};
    j["total_insert_cpu_s"] = total;
    j["refine_rounds"] = refine_rounds;
    j["refine_cpu_s"] = refine_cpu;
    j["growth"] = growth;
    minenav::WriteFileAtomically(json_out, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("mapper_scale_bench", Run, argc, argv); }
