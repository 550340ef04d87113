#pragma once
// The subcommands of the `fleet` tool (fleet/README.md, "Commands").

#include <string>
#include <vector>

#include "fleet/fleet_file.h"

namespace minenav {

// The folder of the running program (${BIN}: the fleet's processes are built beside it).
std::string ProgramFolder();

// Reads and parses FLEETFILE with the built-ins OUT = `out`, BIN = `bin`, FLEET_DIR = its
// folder and `override_words` (NAME=VALUE), then keeps the processes of `groups`
// (comma-separated, "" = all) and, when `resolve_programs`, resolves each program (its
// path, looked up on $PATH when it has no '/'). Throws InputError naming file, line and key.
FleetSpec LoadFleet(const std::string& path, const std::vector<std::string>& override_words, const std::string& out,
                    const std::string& bin, const std::string& groups, bool resolve_programs);

// Comma-separated names into a list ("" = none).
std::vector<std::string> SplitCommaList(const std::string& text);

// `fleet run FLEETFILE [NAME=VALUE...]`: starts and supervises the fleet (supervisor_node.h).
int RunSupervisorCommand(std::vector<std::string>& args);
// `fleet check FLEETFILE [NAME=VALUE...]`: validates and prints the start plan.
int RunCheckCommand(const std::vector<std::string>& args);
// `fleet status`: every process heard on HEARTBEAT, as a table.
int RunStatusCommand(const std::vector<std::string>& args);
// `fleet units FLEETFILE UNITDIR [NAME=VALUE...]`: systemd units (systemd_units.h).
int RunUnitsCommand(const std::vector<std::string>& args);

}  // namespace minenav
