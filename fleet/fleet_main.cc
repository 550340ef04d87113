// fleet: runs the fleet of a fleet file on a development machine or for the demo, and
// deploys it as systemd units on a vehicle (fleet/README.md).
//   fleet [run] FLEETFILE [NAME=VALUE ...] | check | status | units   [--help]

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "fleet/fleet_commands.h"

namespace {

constexpr const char* kCommands =
    "Usage: fleet COMMAND [options]   (fleet COMMAND --help for its options)\n"
    "\n"
    "Commands:\n"
    "  run FLEETFILE [NAME=VALUE ...]    start and supervise the fleet (the default command)\n"
    "  check FLEETFILE [NAME=VALUE ...]  validate a fleet file and print its start plan\n"
    "  status                            every process heard on HEARTBEAT, as a table\n"
    "  units FLEETFILE UNITDIR [...]     systemd units (one service per process, a target per group)\n"
    "\n"
    "Exit codes: 0 ok, 2 bad flag or fleet file (one line naming file, line and key), 3 failure.\n";

}  // namespace

int main(int argc, char** argv) {
  minenav::SetLogProgramName("fleet");
  std::vector<std::string> args(argv + 1, argv + argc);
  const std::string command = args.empty() ? "" : args.front();
  if (command.empty() || command == "help" || command == "--help-commands") {
    std::fputs(kCommands, command.empty() ? stderr : stdout);
    return command.empty() ? minenav::kExitUsage : 0;
  }
  if (command == "run") {
    args.erase(args.begin());
    return minenav::RunSupervisorCommand(args);
  }
  if (command != "check" && command != "status" && command != "units") {
    // `fleet FLEETFILE`, and the process's own --help, --print-options-table, ...
    return minenav::RunSupervisorCommand(args);
  }
  args.erase(args.begin());
  minenav::SetLogProgramName("fleet " + command);
  try {
    if (command == "check") return minenav::RunCheckCommand(args);
    if (command == "status") return minenav::RunStatusCommand(args);
    return minenav::RunUnitsCommand(args);
  } catch (const minenav::UsageError& e) {
    std::fprintf(stderr, "fleet %s: error: %s\n", command.c_str(), e.what());
    return minenav::kExitUsage;
  } catch (const minenav::InputError& e) {
    std::fprintf(stderr, "fleet %s: error: %s\n", command.c_str(), e.what());
    return minenav::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fleet %s: failed: %s\n", command.c_str(), e.what());
    return minenav::kExitRuntime;
  }
}
