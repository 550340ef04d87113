#pragma once
// CUTTER_COMMAND / CUTTER_STATE between LCM and the plain structs of cutter_messages.h.
// The FromLcm functions validate: a message with an unknown action or phase or a number
// that is not finite gives nullopt and a one-line reason.

#include <optional>
#include <string>

#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "tracker/cutter_messages.h"

namespace minenav {

cutter_command_t ToLcm(const CutterCommand& c);
std::optional<CutterCommand> CutterCommandFromLcm(const cutter_command_t& m, std::string* why);
cutter_state_t ToLcm(const CutterState& s);
std::optional<CutterState> CutterStateFromLcm(const cutter_state_t& m, std::string* why);

}  // namespace minenav
