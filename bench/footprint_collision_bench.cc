// The exact footprint test (planner/footprint_collision.h, FootprintCollisionChecker::ExactSpare)
// for the miner's rectangle: its quick path (the polygon is its own box: one box-to-segment
// distance per wall) against the general polygon path (every edge against every wall), on the
// same poses in one run. The general path runs on the same rectangle with a fifth vertex in the
// middle of its front edge (the same polygon, not a 4-corner box). Poses: uniform in the middle
// of a crossing of 7 m entries (the CI mission's section), any heading: where a turning miner
// leaves the field's discs undecided. Rounds alternate the order; thread CPU; medians.
//
//   footprint_collision_bench [--quick] [--json-out FILE]

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_util.h"
#include "common/angle.h"
#include "common/file_io.h"
#include "planner/footprint_collision.h"
#include "planner/test_maps.h"

namespace minenav {
namespace {

int Run(int argc, char** argv) {
  const bench::BenchArgs args =
      bench::ParseBenchArgs(argc, argv, "footprint_collision_bench [--quick] [--json-out FILE]");
  const int rounds = args.quick ? 3 : 15;
  const int poses_per_round = 20'000;
  const planner_test::CheckerWorld world(planner_test::Crossing(7.0, 20.0));
  const Footprint box = Footprint::Rectangle(3.3, 10.0);
  const Footprint five = planner_test::WithFrontMidpoint(box);
  const double margin = 0.125;  // the bench clearance 0.1 m plus half the 0.05 m collision step
  const FootprintCollisionChecker quick(world.index, world.field, box, margin);
  const FootprintCollisionChecker general(world.index, world.field, five, margin);

  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-4.0, 4.0), a(-kPi, kPi);
  std::vector<Pose2> poses;
  for (int i = 0; i < poses_per_round; ++i) poses.emplace_back(u(rng), u(rng), a(rng));

  std::vector<double> quick_ns, general_ns;
  int collisions = 0, disagreements = 0;
  const auto time = [&](const FootprintCollisionChecker& checker, std::vector<double>& spares) {
    spares.clear();
    const double t0 = bench::Now();
    for (const Pose2& p : poses) spares.push_back(checker.ExactSpare(p, std::cos(p.theta), std::sin(p.theta)));
    return 1e9 * (bench::Now() - t0) / static_cast<double>(poses.size());
  };
  std::vector<double> q, g;
  for (int round = 0; round < rounds; ++round) {
    if (round % 2 == 0) {
      quick_ns.push_back(time(quick, q));
      general_ns.push_back(time(general, g));
    } else {
      general_ns.push_back(time(general, g));
      quick_ns.push_back(time(quick, q));
    }
    collisions = disagreements = 0;
    for (size_t i = 0; i < poses.size(); ++i) {
      collisions += g[i] < 0.0;
      disagreements += (q[i] < 0.0) != (g[i] < 0.0) || (g[i] >= 0.0 && std::abs(q[i] - g[i]) > 1e-9);
    }
  }
  std::printf("footprint_collision_bench: the miner 3.3 x 10 m, margin %.3f m, %d poses in a 7 m crossing, %d rounds\n",
              margin, poses_per_round, rounds);
  std::printf("%-28s %14s %14s\n", "exact test", "ns/test med", "ns/test max");
  std::printf("%-28s %14.0f %14.0f\n", "general polygon path", bench::Median(general_ns), bench::Max(general_ns));
  std::printf("%-28s %14.0f %14.0f\n", "rectangle (box) path", bench::Median(quick_ns), bench::Max(quick_ns));
  std::printf("speed-up %.2fx; %d of %d poses in collision; %d answers or spares differ\n",
              bench::Median(general_ns) / bench::Median(quick_ns), collisions, poses_per_round, disagreements);
  if (!args.json_out.empty()) {
    const nlohmann::json j = {{"poses", poses_per_round},     {"rounds", rounds},
                              {"margin_m", margin},           {"general_ns_median", bench::Median(general_ns)},
                              {"box_ns_median", bench::Median(quick_ns)}, {"collisions", collisions},
                              {"disagreements", disagreements}};
    WriteFileAtomically(args.json_out, j.dump(2) + "\n");
  }
  return disagreements == 0 ? 0 : 1;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) { return minenav::Run(argc, argv); }
