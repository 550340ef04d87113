#pragma once
// The built-in worlds by name, with their survey stations: what `vehicle_sim --generate`
// drives in and what `log_tool generate` writes, from one place.
//   mine      room-and-pillar mine of thesis 5.2.1, serpentine survey (42 stations)
//   research  research-mine style (5.3): narrow entries, irregular pillars, cribs (33)
//   mockup    the indoor mockup corridor of 2.2, clutter not in the map, Table 1's 16 stations
//   loop      the mine, with stations around one pillar closing a loop (24)

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"
#include "common/pose2.h"
#include "sim/mine_generator.h"

namespace minenav {

struct ScenarioOptions {
  std::string kind = "mine";   // one of ScenarioKinds()
  uint64_t seed = 1;           // of the generator (overrides mine.seed and research.seed)
  MineOptions mine;            // mine and loop
  ResearchMineOptions research;
  int stations = 0;            // 0 = the kind's default count (ignored for mockup)
  double heading_variation = 0.6;  // rad, random heading offset bound of the stations
  int loop_row = 0, loop_col = 0;  // loop: the pillar to go around
};

struct GeneratedScenario {
  std::vector<Segment> world;     // what the ladar sees
  std::vector<Segment> map;       // the surveyed map (the world, but for the mockup's clutter)
  std::vector<Station> stations;  // the survey
  std::string name;               // e.g. "mine seed 3"
};

const std::vector<std::string>& ScenarioKinds();
// "" when the options are usable, else one line saying what is wrong.
std::string ValidateScenarioOptions(const ScenarioOptions& options);
// Throws std::invalid_argument for options that ValidateScenarioOptions refuses.
GeneratedScenario GenerateScenario(const ScenarioOptions& options);

// What vehicle_sim runs (thesis 4.8 for the changing world): the world the ladar sees first,
// the surveyed map, the start pose, and the worlds that replace it while the fleet runs.
struct WorldChange {
  int64_t at_us = 0;           // since the simulator's first tick
  std::vector<Segment> world;  // replaces the whole world
  std::string name;
};
struct SimScenario {
  std::vector<Segment> world;
  std::vector<Segment> map;
  Pose2 start;
  std::string name;
  std::vector<WorldChange> changes;  // in time order
};
// A world read from a file: its segments and the name it goes by (the path).
struct NamedWorld {
  std::string name;
  std::vector<Segment> segments;
};

// The times of --world-change-at ("T1,T2,..." s): one per world after the first, each in
// (0, 1e7] s and later than the one before. Throws UsageError saying which rule is broken.
std::vector<int64_t> ParseWorldChangeTimes(const std::string& text, size_t world_count);
// The scenario of `worlds` (the first, then one per change time), or, with no worlds, the
// generated one of `generated`; start = `start` or, without one, the generator's first
// station (0,0,0 for worlds). Throws InputError for a world without segments.
SimScenario MakeSimScenario(const std::vector<NamedWorld>& worlds, const std::vector<int64_t>& change_at_us,
                            const ScenarioOptions& generated, const std::optional<Pose2>& start);

}  // namespace minenav
