#pragma once
// Scenario worlds that change between scans (thesis 4.8, Figure 23): for tests, benchmarks,
// `log_tool survey` with several --world files, and the live fleet.
//
// A scenario is a sequence of line-segment worlds, the survey stations (each names the world
// it sees, as the `world` column of the stations CSV, common/file_io.h), and checks: after
// the stations up to `after_station` have been inserted into a map, the map is judged
// against worlds[world]:
//   - must_stay: wall samples that exist in that world and were seen (not too glancingly)
//     from some earlier station while their wall existed; the map must still hold them.
//     `hidden` marks those no station of the current world sees any more (the wall behind
//     a vending machine, a room behind a closed door): what 4.8 says to leave alone.
//   - must_go: samples of walls that existed when some station saw them, are gone from
//     the judged world, and are seen through (the wall behind is hit farther away, the view
//     not too glancing) from a station of the judged world after the change: the map has
//     the evidence to remove them (4.8.2; nothing is removed for age alone).
//   - must_appear: wall samples of the judged world seen (not too glancingly) from its own
//     stations: coverage of the new world.
// Every sample stands for `sample_step` metres of wall, so counts convert to lengths.
//
// The worlds are small, closed rooms with pillars (so every scan's pose is well
// constrained) in metres; every station lies in free space of the world it sees.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"

namespace minenav {

struct ChangingWorldOptions {
  // m; spacing of the judging samples along the walls.
  double sample_step = 0.05;
  // m; a wall sample counts as seen only within this range of a station (the Typhoon's
  // useful range is 45 m; 20 m keeps the judged walls densely scanned).
  double max_view_range = 20.0;
  // rad; a wall sample counts as seen only when the ray meets the wall at least this
  // steeply (between ray and wall). Glancing views are neither mapped reliably nor
  // evidence for removal.
  double min_view_angle = 0.35;
  // m; depth of one cut of the coal face (the entry grows by this).
  double cut_depth = 1.0;
};

std::string ValidateOptions(const ChangingWorldOptions& options);

struct WallSample {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();  // m, world frame
  bool hidden = false;  // must_stay only: no station of the judged world sees it
};

struct ScenarioCheck {
  std::string label;      // e.g. "after the box is placed"
  int after_station = 0;  // judge after inserting stations[0 .. after_station]
  int world = 0;          // index into ChangingWorldScenario::worlds
  std::vector<WallSample> must_stay;
  std::vector<WallSample> must_go;
  std::vector<WallSample> must_appear;
};

struct ChangingWorldScenario {
  std::string name;         // short identifier: doors_open, door_closed, vending_machine, ...
  std::string description;  // one line
  std::vector<std::vector<Segment>> worlds;
  std::vector<Station> stations;  // in survey order; Station::world indexes `worlds`
  std::vector<ScenarioCheck> checks;
  double sample_step = 0.05;  // m of wall per sample (the options' sample_step)
};

// Figure 23: two rooms joined by a double door; the doors are closed for the first
// stations and open for the last ones (the door leaves must go, the room beyond appears).
ChangingWorldScenario DoorsOpenScenario(const ChangingWorldOptions& options = {});
// The reverse: open for the first stations, closed for the last ones (the door appears;
// the mapped room beyond it is hidden and must stay).
ChangingWorldScenario DoorClosedScenario(const ChangingWorldOptions& options = {});
// 4.8: a slightly trapezoidal box placed against the middle of a long wall (three faces
// visible at once), then taken away again. Two checks: after it is placed (the box
// appears, the wall behind it is hidden and must stay) and after it is gone (its faces
// must go, the wall must be there).
ChangingWorldScenario VendingMachineScenario(const ChangingWorldOptions& options = {});
// A machine (a continuous miner's footprint) parked in a room, then driven away.
ChangingWorldScenario ParkedEquipmentScenario(const ChangingWorldOptions& options = {});
// A dead-end entry whose face is advanced by options.cut_depth between the stations
// (the old face must go, the new face and the longer ribs appear).
ChangingWorldScenario CoalFaceScenario(const ChangingWorldOptions& options = {});

// All of the above, in that order.
std::vector<ChangingWorldScenario> AllChangingWorldScenarios(const ChangingWorldOptions& options = {});
// By name; throws std::invalid_argument naming the known names when there is none.
ChangingWorldScenario ChangingWorldScenarioByName(const std::string& name,
                                                  const ChangingWorldOptions& options = {});
std::vector<std::string> ChangingWorldScenarioNames();

// True when `point` (on some wall) is the first thing a ray from `from` toward it hits in
// `world`, within max_range, at least min_view_angle off the wall's direction.
bool SeesWallPoint(const std::vector<Segment>& world, const Eigen::Vector2d& from, const Eigen::Vector2d& point,
                   double max_range, double min_view_angle);

}  // namespace minenav
