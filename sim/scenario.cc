#include "sim/scenario.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/config.h"
#include "sim/mockup_generator.h"

namespace minenav {

const std::vector<std::string>& ScenarioKinds() {
  static const std::vector<std::string> kinds = {"mine", "research", "mockup", "loop"};
  return kinds;
}

std::string ValidateScenarioOptions(const ScenarioOptions& o) {
  const auto& kinds = ScenarioKinds();
  if (std::find(kinds.begin(), kinds.end(), o.kind) == kinds.end()) return "unknown scenario kind '" + o.kind + "'";
  if (o.stations < 0) return "station count must be >= 0";
  if (o.kind == "mine" || o.kind == "loop") {
    MineOptions m = o.mine;
    m.seed = o.seed;
    return ValidateMineOptions(m);
  }
  if (o.kind == "research") {
    ResearchMineOptions r = o.research;
    r.seed = o.seed;
    return ValidateResearchMineOptions(r);
  }
  return "";
}

GeneratedScenario GenerateScenario(const ScenarioOptions& o) {
  if (const std::string why = ValidateScenarioOptions(o); !why.empty()) throw std::invalid_argument(why);
  GeneratedScenario sc;
  const std::string seed = " seed " + std::to_string(o.seed);
  if (o.kind == "mine" || o.kind == "loop") {
    MineOptions m = o.mine;
    m.seed = o.seed;
    sc.world = GenerateRoomAndPillarMine(m);
    sc.stations = o.kind == "mine"
                      ? MineSurveyStations(m, o.stations > 0 ? o.stations : 42, o.heading_variation)
                      : LoopStations(m, o.stations > 0 ? o.stations : 24, o.loop_row, o.loop_col, o.heading_variation);
    sc.name = (o.kind == "mine" ? "mine" : "loop") + seed;
  } else if (o.kind == "research") {
    ResearchMineOptions r = o.research;
    r.seed = o.seed;
    sc.world = GenerateResearchMine(r);
    sc.stations = ResearchMineStations(r, o.stations > 0 ? o.stations : 33, o.heading_variation);
    sc.name = "research mine" + seed;
  } else {
    const MockupWorld mockup = GenerateIndoorMockup(o.seed);
    sc.world = mockup.World();
    sc.map = mockup.map;
    sc.stations = mockup.stations;
    sc.name = "indoor mockup" + seed;
    return sc;
  }
  sc.map = sc.world;
  return sc;
}

std::vector<int64_t> ParseWorldChangeTimes(const std::string& text, size_t world_count) {
  if (world_count <= 1) {
    if (!text.empty()) throw UsageError("--world-change-at needs more than one --world");
    return {};
  }
  if (text.empty())
    throw UsageError(std::to_string(world_count) + " --world files need --world-change-at with " +
                     std::to_string(world_count - 1) + " time(s)");
  const std::vector<double> t = ParseNumberList(text, "--world-change-at", 0);
  if (t.size() != world_count - 1)
    throw UsageError("--world-change-at: '" + text + "' has " + std::to_string(t.size()) + " time(s), expected " +
                     std::to_string(world_count - 1) + " (one per --world after the first)");
  std::vector<int64_t> us;
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || t[i] <= 0.0 || t[i] > 1e7)
      throw UsageError("--world-change-at: '" + text + "': times must be in (0, 1e7] s");
    if (i > 0 && t[i] <= t[i - 1]) throw UsageError("--world-change-at: '" + text + "': times must increase");
    us.push_back(std::llround(t[i] * 1e6));
  }
  return us;
}

SimScenario MakeSimScenario(const std::vector<NamedWorld>& worlds, const std::vector<int64_t>& change_at_us,
                            const ScenarioOptions& generated, const std::optional<Pose2>& start) {
  if (!worlds.empty() && change_at_us.size() + 1 != worlds.size())
    throw std::invalid_argument("MakeSimScenario: one change time per world after the first");
  for (const NamedWorld& w : worlds)
    if (w.segments.empty()) throw InputError(w.name + ": the world has no segments");
  SimScenario sc;
  std::optional<Pose2> first_station;
  if (!worlds.empty()) {
    sc.world = sc.map = worlds.front().segments;
    sc.name = worlds.front().name;
    for (size_t k = 1; k < worlds.size(); ++k)
      sc.changes.push_back({change_at_us[k - 1], worlds[k].segments, worlds[k].name});
  } else {
    if (const std::string why = ValidateScenarioOptions(generated); !why.empty()) throw UsageError(why);
    GeneratedScenario g = GenerateScenario(generated);
    sc.world = std::move(g.world);
    sc.map = std::move(g.map);
    sc.name = std::move(g.name);
    first_station = g.stations.front().pose;
  }
  sc.start = start.value_or(first_station.value_or(Pose2()));
  return sc;
}

}  // namespace minenav
