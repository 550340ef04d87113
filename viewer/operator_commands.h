#pragma once
// Operator commands from the page (start, pause, resume, abort, e-stop) into the
// coordinator's coordinator_command_t on COORDINATOR_COMMAND. The only thing the viewer
// ever publishes: it moves the vehicle only through the coordinator, and only when the
// bridge was started with --allow-commands.
//
// The page sends the JSON {"command": "PAUSE"} on its client channel. Anything else (other
// fields, another command, LOAD_MISSION with a file name, a payload over 1 KB) is refused
// with one line. Issue 16 will authenticate commands: CommandAuthority is where the
// signature goes (today's UnsignedCommandAuthority passes the command on unchanged).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "minenav/coordinator_command_t.hpp"

namespace minenav {

// Issue 16's seam: every command the bridge publishes passes here last. Returns "" when
// the command may go out (after signing it), else why not in one line.
class CommandAuthority {
 public:
  virtual ~CommandAuthority() = default;
  virtual std::string Authorize(coordinator_command_t& command) = 0;
};

// Until commands are signed: every command passes as it is.
class UnsignedCommandAuthority final : public CommandAuthority {
 public:
  std::string Authorize(coordinator_command_t&) override { return ""; }
};

struct OperatorCommandResult {
  std::optional<coordinator_command_t> command;  // set when accepted
  std::string error;                              // one line when refused
};

class OperatorCommands {
 public:
  // allow = false refuses every command (the bridge's default).
  OperatorCommands(bool allow, std::unique_ptr<CommandAuthority> authority);

  // The page's payload at clock time `now` (us): the command to publish, or why not.
  OperatorCommandResult Accept(std::string_view payload, int64_t now);

  bool allowed() const { return allow_; }
  int64_t accepted() const { return seq_; }
  int64_t refused() const { return refused_; }

 private:
  OperatorCommandResult Refuse(std::string why);

  bool allow_;
  std::unique_ptr<CommandAuthority> authority_;
  int64_t seq_ = 0;
  int64_t refused_ = 0;
};

// "START" -> coordinator_command_t::START, ...; nullopt for anything else (LOAD_MISSION too).
std::optional<int8_t> OperatorCommandCode(std::string_view name);

}  // namespace minenav
