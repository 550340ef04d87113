// Contour mapper on the synthetic room-and-pillar mine of thesis 5.2: 42 stations,
// 2048-point Typhoon scans, initial poses = truth + Gaussian noise (σ 0.33 m, 3.33° by
// default), the first scan fixed at its true pose. Inserts every scan, then runs a final
// concurrent refinement, and reports against ground truth: max pose error, map deviation
// from the true walls (mean, max), coverage of the true scan points, contours / segments /
// length, total time and the median time to insert one scan.
//
//   mapper_synthetic_mine_bench [--seed 1] [--stations 42] [--sigma_xy 0.33]
//                               [--sigma_theta_deg 3.33] [--refine_rounds 10] [--json_out FILE]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/segment_index.h"
#include "mapper/contour_map_io.h"
#include "mapper/contour_mapper.h"
#include "evaluation/map_evaluation.h"
#include "sensor_driver/ladar_simulator.h"
#include "sim/mine_generator.h"

namespace {

using minenav::Pose2;
namespace mapper = minenav::mapper;

double Seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct PoseErrors {
  double max_translation = 0.0, max_heading = 0.0, mean_translation = 0.0;
};
PoseErrors Errors(const std::vector<mapper::MappedScan>& scans, const std::vector<Pose2>& truth) {
  PoseErrors e;
  for (size_t k = 0; k < scans.size(); ++k) {
    const double t = minenav::TranslationDistance(scans[k].pose, truth[k]);
    e.max_translation = std::max(e.max_translation, t);
    e.max_heading = std::max(e.max_heading, minenav::HeadingDistance(scans[k].pose, truth[k]));
    e.mean_translation += t / static_cast<double>(scans.size());
  }
  return e;
}

int Run(int argc, char** argv) {
  int seed = 1, stations = 42, refine_rounds = 10;
  double sigma_xy = 0.33, sigma_theta_deg = 3.33;
  std::string json_out, map_out;
  minenav::ConfigSchema schema("mapper_synthetic_mine_bench",
                               "Contour mapper on the synthetic room-and-pillar mine of thesis 5.2.");
  schema.AddInt("seed", &seed, "seed of the mine, the scans and the initial-pose noise", 0, 1000000);
  schema.AddInt("stations", &stations, "survey stations", 2, 1000);
  schema.AddDouble("sigma_xy", &sigma_xy, "m", "initial pose noise, x and y", 0.0, 5.0);
  schema.AddDouble("sigma_theta_deg", &sigma_theta_deg, "deg", "initial heading noise", 0.0, 45.0);
  schema.AddInt("refine_rounds", &refine_rounds, "concurrent refinement rounds at the end (0 = none)", 0, 1000);
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  schema.AddString("map_out", &map_out, "write the contour map JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  minenav::MineOptions mine;
  mine.seed = static_cast<uint64_t>(seed);
  const std::vector<minenav::Segment> world = minenav::GenerateRoomAndPillarMine(mine);
  const std::vector<minenav::Station> survey = minenav::MineSurveyStations(mine, stations);
  const minenav::StaticSegmentIndex grid(world);
  const minenav::LadarSimulator sim(minenav::LadarModel::Typhoon(), static_cast<uint64_t>(seed));
  const minenav::LadarSimulator ideal(minenav::LadarModel::Typhoon().Ideal(), static_cast<uint64_t>(seed));

  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> nxy(0.0, sigma_xy), nth(0.0, minenav::DegToRad(sigma_theta_deg));

  mapper::ContourMapperOptions options;
  options.refinement.max_rounds = std::max(1, refine_rounds);
  mapper::ContourMapper cm(options);
  std::vector<Pose2> truth, initial_poses;
  std::vector<double> insert_s, insert_cpu_s;
  std::vector<Eigen::Vector2d> true_points;
  int refused = 0;
  const double start = Seconds();
  const std::clock_t cpu_start = std::clock();
  for (size_t k = 0; k < survey.size(); ++k) {
    const Pose2 t = survey[k].pose;
    const Pose2 initial = k == 0 ? t : Pose2(t.x + nxy(rng), t.y + nxy(rng), t.theta + nth(rng));
    const minenav::LadarScan scan = sim.Simulate(grid, t, Pose2(), static_cast<int64_t>(k) * 100000, static_cast<int64_t>(k));
    const double t0 = Seconds();
    const std::clock_t c0 = std::clock();
    const mapper::InsertResult r = cm.InsertScan(scan, initial);
    insert_s.push_back(Seconds() - t0);
    insert_cpu_s.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    if (!r.accepted) {
      ++refused;
      std::fprintf(stderr, "scan %zu refused: %s\n", k, r.reason.c_str());
      continue;
    }
    truth.push_back(t);
    initial_poses.push_back(initial);
    const auto pts = minenav::ScanPointsInWorld(ideal.Simulate(grid, t, Pose2(), 0, static_cast<int64_t>(k)), t);
    true_points.insert(true_points.end(), pts.begin(), pts.end());
    std::fprintf(stderr, "scan %2zu: %6.3f s, error %.4f m %.3f deg, %d contours (%s)\n", k, insert_s.back(),
                 minenav::TranslationDistance(r.pose, t), minenav::RadToDeg(minenav::HeadingDistance(r.pose, t)),
                 cm.map().NumContours(), r.reason.c_str());
  }
  const double insert_total = Seconds() - start;
  const PoseErrors before = Errors(cm.scans(), truth);
  const mapper::MapDeviation dev_before = mapper::ContourDeviation(cm.map(), world);
  double refine_s = 0.0;
  mapper::ConcurrentRefinementResult refinement;
  if (refine_rounds > 0) {
    const double t0 = Seconds();
    refinement = cm.Refine();
    refine_s = Seconds() - t0;
  }
  const double total_s = Seconds() - start;
  // CPU time of this process: the wall-clock figures include whatever else the machine runs.
  const double cpu_s = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  const PoseErrors after = Errors(cm.scans(), truth);
  const mapper::MapDeviation dev = mapper::ContourDeviation(cm.map(), world);
  const double coverage = mapper::Coverage(true_points, cm.map(), 0.10);
  const mapper::ContourMap& map = cm.map();

  std::printf("mapper_synthetic_mine_bench: %zu segments, %d stations, Typhoon 2048 points, initial noise %.2f m / %.2f deg, seed %d\n",
              world.size(), stations, sigma_xy, sigma_theta_deg, seed);
  std::printf("%-48s %12s %12s\n", "measure", "inserted", "refined");
  std::printf("%-48s %12.4f %12.4f\n", "max pose error (m)", before.max_translation, after.max_translation);
  std::printf("%-48s %12.4f %12.4f\n", "mean pose error (m)", before.mean_translation, after.mean_translation);
  std::printf("%-48s %12.4f %12.4f\n", "max heading error (deg)", minenav::RadToDeg(before.max_heading),
              minenav::RadToDeg(after.max_heading));
  std::printf("%-48s %12.4f %12.4f\n", "map deviation from true walls, mean (m)", dev_before.mean, dev.mean);
  std::printf("%-48s %12.4f %12.4f\n", "map deviation from true walls, max (m)", dev_before.max, dev.max);
  std::printf("%-48s %12s %12.4f\n", "true scan points within 10 cm of a contour", "", coverage);
  std::printf("%-48s %12s %12d\n", "contours", "", map.NumContours());
  std::printf("%-48s %12s %12d\n", "segments", "", map.NumSegments());
  std::printf("%-48s %12s %12.1f\n", "contour length (m)", "", map.TotalLength());
  std::printf("%-48s %12s %12d\n", "scans refused", "", refused);
  std::printf("%-48s %12s %12.3f\n", "median insert time, wall clock (s per scan)", "", Median(insert_s));
  std::printf("%-48s %12s %12.3f\n", "median insert time, CPU (s per scan)", "", Median(insert_cpu_s));
  std::printf("%-48s %12s %12.3f\n", "all inserts (s)", "", insert_total);
  std::printf("%-48s %12s %12.3f\n", "final concurrent refinement (s)", "", refine_s);
  std::printf("%-48s %12s %12.3f\n", "total, wall clock (s)", "", total_s);
  std::printf("%-48s %12s %12.3f\n", "total, CPU time of this process (s)", "", cpu_s);
  std::printf("(refinement: %d rounds, %s; largest deviation at (%.2f, %.2f) on contour %d)\n", refinement.rounds,
              refinement.reason.c_str(), dev.worst_point.x(), dev.worst_point.y(), dev.worst_contour);

  if (!map_out.empty()) mapper::SaveContourMapJson(map_out, map);
  if (!json_out.empty()) {
    nlohmann::json j;
    j["benchmark"] = "mapper_synthetic_mine_bench";
    j["seed"] = seed;
    j["stations"] = stations;
    j["segments_in_world"] = world.size();
    j["initial_noise"] = {{"sigma_xy_m", sigma_xy}, {"sigma_theta_deg", sigma_theta_deg}};
    auto pose_json = [](const PoseErrors& e) {
      return nlohmann::json{{"max_translation_m", e.max_translation}, {"mean_translation_m", e.mean_translation},
                            {"max_heading_deg", minenav::RadToDeg(e.max_heading)}};
    };
    j["pose_error_inserted"] = pose_json(before);
    j["pose_error_refined"] = pose_json(after);
    j["map_deviation_inserted"] = {{"mean_m", dev_before.mean}, {"max_m", dev_before.max}};
    j["map_deviation_refined"] = {{"mean_m", dev.mean}, {"max_m", dev.max}};
    j["coverage_within_10cm"] = coverage;
    j["contours"] = map.NumContours();
    j["contour_segments"] = map.NumSegments();
    j["contour_length_m"] = map.TotalLength();
    j["scans_refused"] = refused;
    j["median_insert_s"] = Median(insert_s);
    j["median_insert_cpu_s"] = Median(insert_cpu_s);
    j["inserts_s"] = insert_total;
    j["refinement_s"] = refine_s;
    j["refinement_rounds"] = refinement.rounds;
    j["total_s"] = total_s;
    j["total_cpu_s"] = cpu_s;
    minenav::WriteFileAtomically(json_out, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("mapper_synthetic_mine_bench", Run, argc, argv); }
