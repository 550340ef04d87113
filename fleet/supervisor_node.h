#pragma once
// `fleet run`: the supervisor as a node of the fleet (fleet/README.md). It starts the
// processes of a fleet file in their order, reaps them, restarts them by their policy
// (Supervisor, supervisor.h), listens to HEARTBEAT for readiness and the status table,
// publishes its own HEARTBEAT (state WARN while something is restarting or given up, the
// summary as message), prints the table every status_period and on SIGUSR1, and stops the
// whole fleet on SIGINT/SIGTERM: SIGINT to every process at once, SIGKILL to those still
// running after stop_grace.

#include <cstdint>
#include <map>
#include <string>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "fleet/fleet_file.h"
#include "fleet/restart_policy.h"
#include "fleet/supervisor.h"

namespace minenav {

struct SupervisorOptions {
  std::string groups;           // comma-separated host groups to run; "" = all
  std::string out;              // output folder: ${OUT}, the processes' logs (NAME.log)
  double status_period = 10.0;  // s between status tables on stdout; 0 = only on SIGUSR1 and at the end
  double stop_grace = 5.0;      // s between SIGINT and SIGKILL when stopping a process
  RestartOptions restart;
};
void DeclareOptions(ConfigSchema& schema, SupervisorOptions& options);

class SupervisorNode {
 public:
  // `runtime` is started. The programs of `fleet` are resolved (ResolveProgram).
  SupervisorNode(NodeRuntime& runtime, FleetSpec fleet, const SupervisorOptions& options);

  // Supervises until SIGINT/SIGTERM or until the fleet ends by itself, then stops every
  // process. Returns the exit code: 0 after a signal, else the fleet's end (FleetEnd).
  int Run();

 private:
  void Poll(int64_t now);
  void Start(size_t i, int64_t now);
  void RequestStop(size_t i, int64_t now);
  void ReapExits(int64_t now);
  void StopFleet(const std::string& reason);
  void PrintEvents();
  void PrintStatus(int64_t now) const;

  NodeRuntime& runtime_;
  SupervisorOptions options_;
  Supervisor supervisor_;
  std::map<size_t, pid_t> running_;         // process index -> pid
  std::map<size_t, int64_t> kill_at_;       // SIGKILL due (stopped for readiness)
};

}  // namespace minenav
