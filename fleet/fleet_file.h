#pragma once
// The fleet file: which processes make up a fleet, how each is started, on which host
// group it runs, when it starts (after which others, once they are ready) and what happens
// when it exits (fleet/README.md, "The fleet file"). `fleet run` supervises what it lists;
// `fleet units` turns it into systemd units for a vehicle.
//
//   [variables]
//   WORLD = ${OUT}/mine.json
//
//   [process vehicle_sim]
//   command  = ${BIN}/vehicle_sim --world ${WORLD}
//   group    = vehicle
//   restart  = on-failure
//   ready    = heartbeat
//
// Plain text, `key = value` like the processes' config files. The parser is pure (text in,
// FleetSpec out): every error is an InputError of one line naming the file, the line and
// the key.

#include <map>
#include <string>
#include <vector>

namespace minenav {

enum class RestartPolicy { kNever, kOnFailure, kAlways };
const char* ToString(RestartPolicy policy);

// When a process counts as ready, so that the processes started `after` it may start.
enum class Readiness {
  kStarted,    // as soon as it is started
  kHeartbeat,  // a HEARTBEAT from it in state OK or WARN: its node loop runs
  kOk,         // a HEARTBEAT from it in state OK
  kExited,     // it exited 0: a one-shot step (generating a world) the others need done
};
const char* ToString(Readiness readiness);

// What `command` and `env.*` values may use besides the file's [variables]: the output
// folder, the folder of the fleet's programs and the folder of the fleet file.
inline constexpr const char* kOutVariable = "OUT";
inline constexpr const char* kBinVariable = "BIN";
inline constexpr const char* kFleetDirVariable = "FLEET_DIR";

struct ProcessSpec {
  std::string name;               // section name: log file, unit and table name
  std::vector<std::string> argv;  // program and arguments, variables expanded
  std::string group;              // host group (vehicle, base, ...)
  RestartPolicy restart = RestartPolicy::kOnFailure;
  std::vector<std::string> after;  // started once these are ready
  Readiness ready = Readiness::kStarted;
  double ready_timeout = 30.0;  // s: not ready by then counts as a failure (stopped, restarted)
  // Its name (and instance, "name:instance") in HEARTBEAT; "" = it publishes none.
  std::string heartbeat_process;
  std::string heartbeat_instance;
  bool required = false;    // given up or failed for good: the whole fleet stops (exit 3)
  bool ends_fleet = false;  // exited for good: the whole fleet stops with its exit code
  bool stdout_to_log = false;  // stdout into the log file too (default: the supervisor's stdout)
  std::map<std::string, std::string> env;  // extra environment variables
  std::string file;                        // the fleet file, and the line of its section
  int line = 0;
  std::map<std::string, int> key_lines;    // line of each key given (for later errors)

  std::string Where() const;                        // "FILE:LINE" of its section
  std::string Where(const std::string& key) const;  // "FILE:LINE: key" (the section's line if absent)
  bool has_heartbeat() const { return !heartbeat_process.empty(); }
};

struct FleetSpec {
  std::string source;  // the file's name, for messages
  std::map<std::string, std::string> variables;  // every variable in force, built-ins included
  std::vector<ProcessSpec> processes;            // in file order
  std::vector<std::string> Groups() const;       // distinct, in order of first use
  const ProcessSpec* Find(const std::string& name) const;
};

// Parses a fleet file. `builtins` are OUT, BIN and FLEET_DIR (the file may not redefine
// them); `overrides` are NAME=VALUE from the command line (they replace a [variables]
// default, or define a variable the file uses without one). Throws InputError naming
// source, line and key: unknown section or key, a key given twice, a bad value, a variable
// used but not defined, an override no one uses, an `after` naming no process, a cycle.
FleetSpec ParseFleetFile(const std::string& text, const std::string& source,
                         const std::map<std::string, std::string>& builtins,
                         const std::map<std::string, std::string>& overrides);

// The processes of the given host groups (all when `groups` is empty). An `after` naming a
// process of another group is dropped: that one runs on another host. Throws InputError
// for a group no process is in.
FleetSpec SelectGroups(const FleetSpec& fleet, const std::vector<std::string>& groups);

// Splits "NAME=VALUE" command-line words into overrides; throws InputError on a word
// without '=' or with a bad name.
std::map<std::string, std::string> ParseOverrides(const std::vector<std::string>& words);

// The indices of `fleet.processes` in an order where each comes after those it waits for
// (file order among equals).
std::vector<size_t> StartOrder(const FleetSpec& fleet);

// A command as one line a shell would read back the same (for messages and unit files).
std::string QuoteCommand(const std::vector<std::string>& argv);

}  // namespace minenav
