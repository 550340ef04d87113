#include "sim/scenario.h"

#include <algorithm>
#include <stdexcept>

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

}  // namespace minenav
