#include "bench/planner_scenarios.h"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <utility>

#include "bench/bench_util.h"
#include "sim/mine_generator.h"

namespace minenav::bench {
namespace {

constexpr double kPillar = 12.0;

// The mine's lines for entries and crosscuts `room` m wide between 12 m pillars.
struct Layout {
  double room, pitch;
  // Entry k (0 = south boundary entry) centre line y; crosscut c centre line x.
  double EntryY(int k) const { return 0.5 * room + k * pitch; }
  double CrosscutX(int c) const { return 0.5 * room + c * pitch; }
  // A face across an entry 1 m before the crossing east of pillar column c: a dead end 11 m long.
  double FaceX(int c) const { return room + c * pitch + kPillar - 1.0; }
};

// The first free pose from `p` moving by `step` (at most `tries` times); p itself if none.
Pose2 NudgeFree(const Se2Planner& planner, Pose2 p, const Eigen::Vector2d& step, int tries) {
  for (int i = 0; i < tries && !planner.PoseFree(p); ++i) {
    p.x += step.x();
    p.y += step.y();
  }
  return p;
}

}  // namespace

const std::vector<std::string>& PlannerScenarioNames() {
  static const std::vector<std::string> names = {"box_cut", "slab_cut", "back_out", "turn", "long_entry", "long"};
  return names;
}

size_t PlannerScenarios::MapIndex(const PlannerRequest& request) const {
  return static_cast<size_t>(
      std::find_if(planners.begin(), planners.end(), [&](const auto& p) { return p.get() == request.planner; }) -
      planners.begin());
}

PlannerScenarios BuildPlannerScenarios(int seeds, int instances, double displacement, const Footprint& footprint,
                                       const Se2PlannerOptions& options, double room_width) {
  const Layout layout{room_width, kPillar + room_width};
  PlannerScenarios s;
  std::vector<std::unique_ptr<Se2Planner>>& planners = s.planners;
  std::vector<PlannerRequest>& requests = s.requests;
  for (int seed = 1; seed <= seeds; ++seed) {
    MineOptions mine;
    mine.pillar_rows = 4;
    mine.pillar_cols = 6;
    mine.pillar_size = kPillar;
    mine.room_width = layout.room;
    mine.midpoint_displacement = displacement;
    mine.seed = static_cast<uint64_t>(seed);
    const std::vector<Segment> plain = GenerateRoomAndPillarMine(mine);
    const Eigen::Vector2d size = MinePanelSize(mine);
    std::mt19937 rng(static_cast<unsigned>(seed));
    // Faces: across entry k beside pillar column c (entries 0..3, so the crosscut behind the
    // dead end has a north arm to back into).
    std::vector<std::pair<int, int>> faces;
    for (int i = 0; i < instances; ++i) faces.push_back({i % 4, 1 + static_cast<int>(rng() % 5)});
    std::vector<Segment> with_faces = plain;
    for (const auto& [k, c] : faces) {
      const double xf = layout.FaceX(c);
      with_faces.push_back({xf, k * layout.pitch - 1.0, xf, k * layout.pitch + layout.room + 1.0});
    }
    for (const std::vector<Segment>* m : {&plain, static_cast<const std::vector<Segment>*>(&with_faces)}) {
      const double t0 = Now();
      planners.push_back(std::make_unique<Se2Planner>(*m, footprint, options));
      s.setup_s.push_back(Now() - t0);
      s.maps.push_back(*m);
      if (!planners.back()->setup_error().empty())
        throw std::runtime_error("planner setup: " + planners.back()->setup_error());
    }
    const Se2Planner& open = *planners[planners.size() - 2];
    const Se2Planner& faced = *planners.back();
    std::uniform_real_distribution<double> back(10.0, 18.0), lateral(-0.4, 0.4), yaw(-0.08, 0.08);
    for (const auto& [k, c] : faces) {
      const double xf = layout.FaceX(c), y = layout.EntryY(k);
      const Eigen::Vector2d away(-0.1, 0.0);
      const Pose2 at_face = NudgeFree(faced, Pose2(xf - 5.6, y, 0.0), away, 20);
      const double shift = 0.7;
      const Pose2 left = NudgeFree(faced, Pose2(xf - 5.6, y + shift, 0.0), away, 20);
      const Pose2 right = NudgeFree(faced, Pose2(xf - 5.6, y - shift, 0.0), away, 20);
      const Pose2 behind(std::max(5.5, at_face.x - back(rng)), y + lateral(rng), yaw(rng));
      requests.push_back({"box_cut", &faced, behind, at_face});
      requests.push_back({"slab_cut", &faced, left, right});
      // Backing out: rear first round the corner into the north arm of the crosscut behind.
      requests.push_back({"back_out", &faced, at_face, Pose2(layout.CrosscutX(c), y + 12.0, -kPi / 2)});
    }
    // Turns from an entry into a crosscut at inner crossings, left or right.
    for (int i = 0; i < instances; ++i) {
      const int k = 1 + i % 3, c = 1 + static_cast<int>(rng() % 5);
      const double side = i % 2 == 0 ? 1.0 : -1.0;
      requests.push_back({"turn", &open, Pose2(layout.CrosscutX(c) - 12.0, layout.EntryY(k) + lateral(rng), yaw(rng)),
                          Pose2(layout.CrosscutX(c), layout.EntryY(k) + side * 12.0, side * kPi / 2)});
    }
    // Along a whole entry, > 100 m, with a lateral offset and a heading change at the ends.
    for (int i = 0; i < instances; ++i) {
      const int k = i % 5;
      requests.push_back({"long_entry", &open, Pose2(6.5, layout.EntryY(k) + lateral(rng), yaw(rng)),
                          Pose2(size.x() - 6.5, layout.EntryY(k) + lateral(rng), yaw(rng))});
    }
    // Across the section, corner to corner.
    for (int i = 0; i < instances; ++i) {
      const bool flip = i % 2 == 1;
      const Pose2 a(10.0 + lateral(rng), layout.EntryY(0) + lateral(rng), 0.0);
      const Pose2 b(size.x() - 10.0 + lateral(rng), layout.EntryY(4) + lateral(rng), i % 4 < 2 ? 0.0 : kPi);
      requests.push_back({"long", &open, flip ? b : a, flip ? a : b});
    }
  }
  return s;
}

}  // namespace minenav::bench
