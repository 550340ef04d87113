// Loop closure by concurrent refinement (thesis 4.7, Figure 22): stations around a pillar of
// the synthetic room-and-pillar mine, Typhoon scans trimmed to a short range so that the two
// ends of the loop only meet at its closure, and dead-reckoned initial poses with
// accumulated drift (scale and heading drift per metre).
//   A. "dead reckoning": the map is built at the dead-reckoned poses as they are (expansion
//      and fitting, no pose estimation), then refined concurrently. Pose errors before and
//      after show what concurrent refinement alone recovers.
//   B. "mapper": the full cycle, each scan's initial pose = the previous refined pose
//      composed with the odometry motion since it; then a final concurrent refinement.
//
//   mapper_loop_bench [--seed 1] [--stations 16] [--max_range 15] [--scale_error 0.005]
//                     [--drift_deg_per_m 0.03] [--rounds 20] [--pose_graph true]
//                     [--point_stride 2] [--json_out FILE]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>
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
#include "sim/odometry_model.h"

namespace {

using minenav::Pose2;
namespace mapper = minenav::mapper;

struct Errors {
  double max_t = 0.0, mean_t = 0.0, max_h_deg = 0.0;
};
Errors PoseErrors(const std::vector<Pose2>& est, const std::vector<Pose2>& truth) {
  Errors e;
  for (size_t k = 0; k < est.size(); ++k) {
    const double t = minenav::TranslationDistance(est[k], truth[k]);
    e.max_t = std::max(e.max_t, t);
    e.mean_t += t / static_cast<double>(est.size());
    e.max_h_deg = std::max(e.max_h_deg, minenav::RadToDeg(minenav::HeadingDistance(est[k], truth[k])));
  }
  return e;
}
std::vector<Pose2> Poses(const std::vector<mapper::MappedScan>& scans) {
  std::vector<Pose2> out;
  for (const auto& s : scans) out.push_back(s.pose);
  return out;
}
nlohmann::json ToJson(const Errors& e, const mapper::MapDeviation& d) {
  return {{"max_pose_error_m", e.max_t}, {"mean_pose_error_m", e.mean_t}, {"max_heading_error_deg", e.max_h_deg},
          {"map_deviation_mean_m", d.mean}, {"map_deviation_max_m", d.max}};
}
void Row(const char* name, const Errors& e, const mapper::MapDeviation& d) {
  std::printf("%-34s %10.4f %10.4f %10.3f %10.4f %10.4f\n", name, e.max_t, e.mean_t, e.max_h_deg, d.mean, d.max);
}

int Run(int argc, char** argv) {
  int seed = 1, stations = 16, rounds = 20;
  double max_range = 15.0, scale_error = 0.005, drift_deg_per_m = 0.03;
  std::string json_out;
  bool pose_graph = true;
  int point_stride = mapper::LoopClosureOptions{}.point_stride;
  minenav::ConfigSchema schema("mapper_loop_bench", "Loop closure by concurrent refinement around a pillar.");
  schema.AddInt("seed", &seed, "seed of the mine, scans and odometry errors", 0, 1000000);
  schema.AddInt("stations", &stations, "stations around the loop", 4, 200);
  schema.AddDouble("max_range", &max_range, "m", "scans are trimmed to this range", 2.0, 45.0);
  schema.AddDouble("scale_error", &scale_error, "", "odometry scale error (0.005 = reads 0.5% long)", -0.5, 0.5);
  schema.AddDouble("drift_deg_per_m", &drift_deg_per_m, "deg/m", "odometry heading drift per metre", -10.0, 10.0);
  schema.AddInt("rounds", &rounds, "concurrent refinement rounds at most", 1, 1000);
  double min_decrease = mapper::ConcurrentRefinementOptions{}.min_relative_decrease;
  schema.AddDouble("min_decrease", &min_decrease, "", "refinement stops when a round lowers the total error by less than this fraction", 0.0, 1.0);
  schema.AddBool("pose_graph", &pose_graph, "run the pose-graph step (loop_closure.h) before the rounds");
  schema.AddInt("point_stride", &point_stride, "every k-th point of a scan in the pairwise registrations", 1, 100);
  schema.AddString("json_out", &json_out, "write the results as JSON to this file ('' = none)");
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;

  minenav::MineOptions mine;
  mine.seed = static_cast<uint64_t>(seed);
  const std::vector<minenav::Segment> world = minenav::GenerateRoomAndPillarMine(mine);
  std::vector<Pose2> truth;
  for (const minenav::Station& s : minenav::LoopStations(mine, stations)) truth.push_back(s.pose);
  minenav::OdometryErrorOptions odo;
  odo.scale_error = scale_error;
  odo.heading_drift_per_metre = minenav::DegToRad(drift_deg_per_m);
  odo.translation_noise = 0.005;
  odo.rotation_noise = minenav::DegToRad(0.05);
  const std::vector<Pose2> dead = minenav::DeadReckonAlong(truth, {}, odo, static_cast<uint64_t>(seed));
  const minenav::StaticSegmentIndex grid(world);
  const minenav::LadarSimulator sim(minenav::LadarModel::Typhoon(), static_cast<uint64_t>(seed));
  std::vector<minenav::LadarScan> scans;
  for (size_t k = 0; k < truth.size(); ++k)
    scans.push_back(sim.Simulate(grid, truth[k], Pose2(), static_cast<int64_t>(k) * 100000, static_cast<int64_t>(k)));

  mapper::ContourMapperOptions options;
  options.preprocessing.max_range = max_range;
  options.refinement.max_rounds = rounds;
  options.refinement.loop_closure.enabled = pose_graph;
  options.refinement.min_relative_decrease = min_decrease;
  options.refinement.loop_closure.point_stride = point_stride;

  // A: map at the dead-reckoned poses, then concurrent refinement.
  const std::clock_t a0 = std::clock();
  std::vector<mapper::MappedScan> mapped;
  mapper::ContourMap map_a(options.grid_cell_size);
  for (size_t k = 0; k < scans.size(); ++k) {
    mapped.push_back({mapper::PreprocessScan(scans[k], options.preprocessing), dead[k], k == 0});
    const mapper::MapExpansionResult ex = mapper::ExpandMap(mapped.back().scan, dead[k], map_a, options.expansion);
    mapper::FitContours(ex.Touched(), mapped, map_a, options.fitting);
  }
  const Errors a_before = PoseErrors(Poses(mapped), truth);
  const mapper::MapDeviation a_dev_before = mapper::ContourDeviation(map_a, world);
  const mapper::ConcurrentRefinementResult a_ref = mapper::RefineConcurrently(mapped, map_a, options.refinement);
  const Errors a_after = PoseErrors(Poses(mapped), truth);
  const mapper::MapDeviation a_dev_after = mapper::ContourDeviation(map_a, world);
  const double a_cpu = static_cast<double>(std::clock() - a0) / CLOCKS_PER_SEC;

  // B: the full cycle with odometry deltas composed onto the last refined pose.
  const std::clock_t b0 = std::clock();
  mapper::ContourMapper cm(options);
  std::vector<Pose2> truth_b;
  Pose2 last_refined = dead[0];
  int refused = 0;
  for (size_t k = 0; k < scans.size(); ++k) {
    const Pose2 initial = k == 0 ? dead[0] : last_refined * minenav::Between(dead[k - 1], dead[k]);
    const mapper::InsertResult r = cm.InsertScan(scans[k], initial);
    if (!r.accepted) {
      ++refused;
      std::fprintf(stderr, "B: scan %zu refused: %s\n", k, r.reason.c_str());
      continue;
    }
    last_refined = r.pose;
    truth_b.push_back(truth[k]);
  }
  const Errors b_before = PoseErrors(Poses(cm.scans()), truth_b);
  const mapper::MapDeviation b_dev_before = mapper::ContourDeviation(cm.map(), world);
  const mapper::ConcurrentRefinementResult b_ref = cm.Refine();
  const Errors b_after = PoseErrors(Poses(cm.scans()), truth_b);
  const mapper::MapDeviation b_dev_after = mapper::ContourDeviation(cm.map(), world);
  const double b_cpu = static_cast<double>(std::clock() - b0) / CLOCKS_PER_SEC;

  std::vector<Pose2> dead_k(dead.begin(), dead.end());
  const Errors odometry = PoseErrors(dead_k, truth);
  std::printf("mapper_loop_bench: %d stations around pillar (0, 0), scans trimmed to %.1f m, seed %d\n", stations,
              max_range, seed);
  std::printf("%-34s %10s %10s %10s %10s %10s\n", "poses", "max (m)", "mean (m)", "max (deg)", "dev mean", "dev max");
  std::printf("%-34s %10.4f %10.4f %10.3f\n", "dead reckoning", odometry.max_t, odometry.mean_t, odometry.max_h_deg);
  Row("A: map at dead-reckoned poses", a_before, a_dev_before);
  Row("A: after concurrent refinement", a_after, a_dev_after);
  Row("B: mapper, after inserts", b_before, b_dev_before);
  Row("B: after concurrent refinement", b_after, b_dev_after);
  std::printf("(A: %d rounds, %s, %.1f s CPU; B: %d refused, %d rounds, %s, %.1f s CPU)\n", a_ref.rounds,
              a_ref.reason.c_str(), a_cpu, refused, b_ref.rounds, b_ref.reason.c_str(), b_cpu);
  std::printf("A pose graph: %s\nB pose graph: %s\n", a_ref.loop_closure.reason.c_str(), b_ref.loop_closure.reason.c_str());

  if (!json_out.empty()) {
    nlohmann::json j;
    j["benchmark"] = "mapper_loop_bench";
    j["seed"] = seed;
    j["stations"] = stations;
    j["max_range_m"] = max_range;
    j["dead_reckoning"] = {{"max_pose_error_m", odometry.max_t}, {"max_heading_error_deg", odometry.max_h_deg}};
    j["a_before"] = ToJson(a_before, a_dev_before);
    j["a_after"] = ToJson(a_after, a_dev_after);
    j["a_rounds"] = a_ref.rounds;
    j["a_total_error"] = a_ref.total_error;
    j["a_cpu_s"] = a_cpu;
    j["b_before"] = ToJson(b_before, b_dev_before);
    j["b_after"] = ToJson(b_after, b_dev_after);
    j["b_rounds"] = b_ref.rounds;
    j["b_refused"] = refused;
    j["b_cpu_s"] = b_cpu;
    minenav::WriteFileAtomically(json_out, j.dump(2) + "\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return minenav::bench::RunBenchMain("mapper_loop_bench", Run, argc, argv); }
