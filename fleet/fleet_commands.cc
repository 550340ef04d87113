#include "fleet/fleet_commands.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <sstream>

#include "common/clock.h"
#include "common/config.h"
#include "common/file_io.h"
#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "common/node/node_runtime.h"
#include "fleet/child_launcher.h"
#include "common/node/heartbeat_conversion.h"
#include "fleet/status_table.h"
#include "fleet/supervisor_node.h"
#include "fleet/systemd_units.h"
#include "minenav/heartbeat_t.hpp"

namespace minenav {

namespace fs = std::filesystem;

namespace {

std::string Absolute(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  return (ec ? fs::path(path) : p).lexically_normal().string();
}

std::string DefaultOutFolder() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &tm);
  return std::string("out/fleet-") + stamp;
}

// What ${OUT} and ${BIN} stand for and which groups to read, for `check` and `units`.
struct FleetFileOptions {
  std::string groups;
  std::string out;
  std::string bin = ProgramFolder();
};
void DeclareOptions(ConfigSchema& schema, FleetFileOptions& options, const std::string& where) {
  schema.AddString("groups", &options.groups, "host groups, comma-separated; empty = all");
  schema.AddString("out", &options.out, "the output folder ${OUT} stands for " + where);
  schema.AddString("bin", &options.bin, "the folder ${BIN} stands for " + where + " (default: the folder of this program)");
}

// The positional FLEETFILE and NAME=VALUE words of a parsed schema.
struct FleetArguments {
  std::string path;
  std::vector<std::string> overrides;
};
FleetArguments SplitPositional(const std::vector<std::string>& positional, size_t fixed) {
  if (positional.size() < fixed)
    throw UsageError(fixed == 1 ? "expected FLEETFILE [NAME=VALUE ...] (see --help)"
                                : "expected FLEETFILE UNITDIR [NAME=VALUE ...] (see --help)");
  FleetArguments a;
  a.path = positional[0];
  a.overrides.assign(positional.begin() + static_cast<long>(fixed), positional.end());
  return a;
}

}  // namespace

std::string ProgramFolder() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(".") : self.parent_path().string();
}

std::vector<std::string> SplitCommaList(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto b = item.find_first_not_of(' ');
    const auto e = item.find_last_not_of(' ');
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

FleetSpec LoadFleet(const std::string& path, const std::vector<std::string>& override_words, const std::string& out,
                    const std::string& bin, const std::string& groups, bool resolve_programs) {
  const std::string text = ReadFile(path);
  const std::map<std::string, std::string> builtins = {
      {kOutVariable, Absolute(out)},
      {kBinVariable, Absolute(bin)},
      {kFleetDirVariable, Absolute(fs::path(path).parent_path().empty() ? "." : fs::path(path).parent_path().string())}};
  FleetSpec fleet = SelectGroups(ParseFleetFile(text, path, builtins, ParseOverrides(override_words)), SplitCommaList(groups));
  if (resolve_programs)
    for (ProcessSpec& p : fleet.processes) p.argv[0] = ResolveProgram(p.argv[0], p.Where("command"));
  return fleet;
}

int RunSupervisorCommand(std::vector<std::string>& args) {
  SupervisorOptions options;
  ConfigSchema* parsed = nullptr;
  return RunNodeProcess(
      "fleet",
      "`fleet run FLEETFILE` (or `fleet FLEETFILE`) starts the processes of a fleet file (those of\n"
      "--groups, or all) in their order, supervises them (restart with exponential backoff; a crash\n"
      "loop is given up with a one-line reason), prints a status table every --status-period s and on\n"
      "SIGUSR1, and stops them all on SIGINT/SIGTERM (SIGINT to each, SIGKILL after --stop-grace s).\n"
      "Each process's stderr goes to OUT/NAME.log. NAME=VALUE sets a variable of the fleet file.\n"
      "Other commands: fleet check | status | units (fleet help).",
      args,
      [&](ConfigSchema& schema) {
        parsed = &schema;
        DeclareOptions(schema, options);
        // At least the file: checked in `run`, so that --print-options-table needs none.
        schema.SetPositional("FLEETFILE [NAME=VALUE ...]", 0, 1000);
        schema.AddHelpEpilog(
            "When the fleet ends by itself: exit 0 when every process ended well, or a process with\n"
            "ends_fleet = true exited 0; exit 3 when a required process was given up or failed.\n");
      },
      [&](NodeRuntime& runtime) {
        Validate(options.restart);
        if (!runtime.options().log.empty() || !runtime.options().log_out.empty())
          throw UsageError("the supervisor runs live: --log and --log-out are for the fleet's processes");
        const FleetArguments a = SplitPositional(parsed->positional(), 1);
        // Supervisors of one fleet on two hosts tell their HEARTBEATs apart by their groups.
        if (!parsed->WasSet("instance"))
          parsed->Set("instance", options.groups.empty() ? "all" : options.groups, "the groups it runs");
        if (options.out.empty()) options.out = DefaultOutFolder();
        options.out = Absolute(options.out);
        FleetSpec fleet = LoadFleet(a.path, a.overrides, options.out, ProgramFolder(), options.groups, true);
        std::error_code ec;
        fs::create_directories(options.out, ec);
        if (ec) throw InputError("--out " + options.out + ": cannot create it (" + ec.message() + ")");
        runtime.Start();
        SupervisorNode node(runtime, std::move(fleet), options);
        return node.Run();
      });
}

int RunCheckCommand(const std::vector<std::string>& args) {
  FleetFileOptions file;
  file.out = "out/fleet-<UTC time>";
  ConfigSchema schema("fleet check",
                      "Usage: fleet check FLEETFILE [NAME=VALUE ...] [options]\n"
                      "Reads a fleet file as `fleet run` would (variables, groups, programs on $PATH) and prints\n"
                      "each process in start order: group, what it waits for, readiness, restart policy and\n"
                      "command. Exit 2 with one line naming file, line and key when something is wrong.");
  DeclareOptions(schema, file, "in the plan");
  schema.SetPositional("FLEETFILE [NAME=VALUE ...]", 1, 1000);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  const FleetArguments a = SplitPositional(schema.positional(), 1);
  const FleetSpec fleet = LoadFleet(a.path, a.overrides, file.out, file.bin, file.groups, true);
  std::vector<std::vector<std::string>> rows;
  for (const size_t i : StartOrder(fleet)) {
    const ProcessSpec& p = fleet.processes[i];
    std::string after;
    for (const std::string& d : p.after) after += (after.empty() ? "" : ",") + d;
    std::string flags = std::string(p.required ? "required " : "") + (p.ends_fleet ? "ends_fleet" : "");
    rows.push_back({p.name, p.group, after.empty() ? "-" : after, ToString(p.ready), ToString(p.restart),
                    p.has_heartbeat() ? p.heartbeat_process + (p.heartbeat_instance.empty() ? "" : ":" + p.heartbeat_instance) : "none",
                    flags.empty() ? "-" : flags, QuoteCommand(p.argv)});
  }
  std::printf("%s: %zu processes, groups:", fleet.source.c_str(), fleet.processes.size());
  for (const std::string& g : fleet.Groups()) std::printf(" %s", g.c_str());
  std::printf("\n%s", FormatTable({"process", "group", "after", "ready", "restart", "heartbeat", "flags", "command"}, rows).c_str());
  return 0;
}

int RunStatusCommand(const std::vector<std::string>& args) {
  std::string url, channel = "HEARTBEAT";
  double listen = 2.5;
  ConfigSchema schema("fleet status",
                      "Usage: fleet status [options]\n"
                      "Listens to HEARTBEAT for --for seconds and prints every process heard: pid, age of its last\n"
                      "heartbeat, state, messages handled per second (from two consecutive heartbeats), messages\n"
                      "rejected, and its message (a supervisor's says how its fleet is). Exit 3 when none is heard.");
  schema.AddString("lcm_url", &url, "LCM URL; empty = $LCM_DEFAULT_URL, else the design default");
  schema.AddChannel("heartbeat_channel", &channel, "subscribes", "heartbeat_t", "the fleet's heartbeats");
  schema.AddDouble("for", &listen, "s", "how long to listen (heartbeats come about once a second)", 0.1, 3600.0);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  LcmBus bus(ResolveLcmUrl(url), 1000);
  const WallClock clock;
  HeartbeatMonitor heartbeats;
  Subscribe<heartbeat_t>(bus, channel,
                         [&](const heartbeat_t& m) { heartbeats.Add(HeartbeatSampleFromLcm(m, clock.NowUtime())); });
  NodeRuntime::InstallSignalHandlers();
  const int64_t end = clock.NowUtime() + static_cast<int64_t>(listen * 1e6);
  while (clock.NowUtime() < end && !NodeRuntime::StopSignalled()) bus.HandleFor(50'000);
  if (heartbeats.All().empty()) {
    std::fprintf(stderr, "fleet status: no %s heard on %s in %g s\n", channel.c_str(), bus.url().c_str(), listen);
    return kExitRuntime;
  }
  std::fputs(BusStatusTable(heartbeats, clock.NowUtime()).c_str(), stdout);
  return 0;
}

int RunUnitsCommand(const std::vector<std::string>& args) {
  FleetFileOptions file;
  file.out = "/var/lib/minenav";
  RestartOptions restart;
  UnitOptions units;
  ConfigSchema schema("fleet units",
                      "Usage: fleet units FLEETFILE UNITDIR [NAME=VALUE ...] [options]\n"
                      "Writes a systemd service per process of the fleet file (of --groups, or all) and a target per\n"
                      "host group into UNITDIR: Type=notify with a watchdog for the processes on the node runtime\n"
                      "(those with a heartbeat), the restart policy, backoff and crash loop as Restart=, RestartSec=,\n"
                      "StartLimitBurst= / StartLimitIntervalSec=, `after` as After= / Wants=.");
  DeclareOptions(schema, file, "on the vehicle");
  schema.AddString("prefix", &units.prefix, "unit names are PREFIX-PROCESS.service and PREFIX-GROUP.target");
  schema.AddString("lcm_url", &units.lcm_url, "LCM_DEFAULT_URL of every unit (ttl=1: one hop, vehicle to base station)");
  schema.AddDouble("watchdog_sec", &units.watchdog_sec, "s", "WatchdogSec= of the Type=notify units", 1.0, 3600.0);
  schema.AddDouble("stop_timeout_sec", &units.stop_timeout_sec, "s", "TimeoutStopSec=: SIGINT, then SIGKILL after this",
                   0.1, 3600.0);
  schema.AddString("user", &units.user, "User= of every unit; empty = root");
  schema.AddString("environment_file", &units.environment_file, "EnvironmentFile= (optional: site settings); empty = none");
  DeclareOptions(OptionScope(schema).Nested("restart"), restart);
  schema.SetPositional("FLEETFILE UNITDIR [NAME=VALUE ...]", 2, 1000);
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  Validate(restart);
  const FleetArguments a = SplitPositional(schema.positional(), 2);
  const std::string unit_dir = schema.positional()[1];
  // The programs are the vehicle's (under --bin), not this machine's: not looked up here.
  const FleetSpec fleet = LoadFleet(a.path, a.overrides, file.out, file.bin, file.groups, false);
  units.source_note = "fleet units " + a.path + " ...";
  std::error_code ec;
  fs::create_directories(unit_dir, ec);
  if (ec) throw InputError(unit_dir + ": cannot create it (" + ec.message() + ")");
  for (const UnitFile& u : GenerateUnits(fleet, restart, units)) {
    WriteFileAtomically((fs::path(unit_dir) / u.name).string(), u.text);
    std::printf("%s\n", (fs::path(unit_dir) / u.name).string().c_str());
  }
  return 0;
}

}  // namespace minenav
