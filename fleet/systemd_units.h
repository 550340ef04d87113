#pragma once
// systemd units for a fleet on a vehicle (fleet/README.md, "systemd on a vehicle"): one
// service per process of the fleet file and one target per host group, so the same file
// that `fleet run` supervises on a development machine deploys as services:
//
//   fleet units mission.fleet /etc/systemd/system --groups vehicle --out /var/lib/minenav
//   systemctl daemon-reload && systemctl start minenav-vehicle.target
//
// A process that publishes HEARTBEAT runs on the node runtime, which speaks systemd's
// notify protocol (common/node/node_runtime.h): such a unit is Type=notify with a
// watchdog (READY=1 once the loop runs, WATCHDOG=1 from the loop). Others are Type=simple.
// The fleet file's restart policy maps to Restart=, the first backoff delay to RestartSec=,
// the crash loop to StartLimitBurst= / StartLimitIntervalSec=, `after` to After=/Wants=.
// Pure: text in, text out.

#include <string>
#include <vector>

#include "fleet/fleet_file.h"
#include "fleet/restart_policy.h"

namespace minenav {

struct UnitOptions {
  std::string prefix = "minenav";  // units are PREFIX-NAME.service and PREFIX-GROUP.target
  // The bus on the vehicle LAN: ttl=1 reaches the base station one hop away (DESIGN.md, "The bus").
  std::string lcm_url = "udpm://239.255.76.67:7667?ttl=1&recv_buf_size=4194304";
  double watchdog_sec = 10.0;  // WatchdogSec= of Type=notify units; the loop pings at half of it
  double stop_timeout_sec = 5.0;  // TimeoutStopSec=: SIGINT first, SIGKILL after this
  std::string user;               // User= ("" = root)
  // Optional file of site settings (LCM_DEFAULT_URL for another LAN, ...); its values win.
  std::string environment_file = "/etc/minenav/minenav.env";
  std::string source_note;  // the command that generated the units, for their header
};

struct UnitFile {
  std::string name;  // e.g. minenav-vehicle_sim.service
  std::string text;
};

// One service per process of `fleet` and one target per group; the target Wants= its
// group's services, each service is PartOf= its target (stopping the target stops them).
std::vector<UnitFile> GenerateUnits(const FleetSpec& fleet, const RestartOptions& restart, const UnitOptions& options);

// A command line as systemd's ExecStart= reads it back into the same words ('%' and '$'
// escaped, words with blanks or quotes double-quoted).
std::string SystemdCommandLine(const std::vector<std::string>& argv);

}  // namespace minenav
