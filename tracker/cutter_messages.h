#pragma once
// The cutter appendages' command and state as plain C++ (channels CUTTER_COMMAND and
// CUTTER_STATE, lcmtypes/cutter_command_t.lcm and cutter_state_t.lcm; thesis 6.4.1). The
// cutter library (tracker/cutter.h) speaks these; the simulated cutterhead (sim/cutterhead.h)
// obeys them; tracker/cutter_conversions.h converts them to and from LCM. Header only, no
// LCM, so the simulator can include it without linking the tracker.

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "common/geometry.h"

namespace minenav {

struct CutterCommand {
  // The values of cutter_command_t's constants.
  enum class Action { kIdle = 0, kDrumOn = 1, kDrumOff = 2, kSetBoom = 3, kSump = 4, kShear = 5, kStop = 6 };
  int64_t utime = 0;  // us
  int64_t seq = 0;
  Action action = Action::kIdle;
  double boom_height = 0.0;   // m above the floor, target of kSetBoom
  double sump_depth = 0.0;    // m: to the vehicle the advance of this sump (informative); in a cut task
                              // (channel CUT_TASK) the depth of the whole cut
  std::optional<Segment> face;  // m, map frame; none when the message's two points coincide
};

struct CutterState {
  // The values of cutter_state_t's constants.
  enum class Phase { kIdle = 0, kSquaring = 1, kSumping = 2, kShearing = 3, kCleaning = 4, kFault = 5 };
  int64_t utime = 0;  // us
  Phase phase = Phase::kIdle;
  bool drum_on = false;
  double boom_height = 0.0;    // m above the floor
  double sumped_depth = 0.0;   // m advanced since the last kSump
  double coal_removed = 0.0;   // m^2 of plan area cut so far
  std::string message;         // one line; "refused ...: reason" after a refused command
};

// A number as the one-line reasons of both sides write it: fixed, `digits` decimals.
inline std::string CutterNumber(double v, int digits = 2) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(digits);
  os << v;
  return os.str();
}

inline const char* ToString(CutterCommand::Action a) {
  switch (a) {
    case CutterCommand::Action::kIdle: return "IDLE";
    case CutterCommand::Action::kDrumOn: return "DRUM_ON";
    case CutterCommand::Action::kDrumOff: return "DRUM_OFF";
    case CutterCommand::Action::kSetBoom: return "SET_BOOM";
    case CutterCommand::Action::kSump: return "SUMP";
    case CutterCommand::Action::kShear: return "SHEAR";
    case CutterCommand::Action::kStop: return "STOP";
  }
  return "?";
}

}  // namespace minenav
