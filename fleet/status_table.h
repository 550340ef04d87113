#pragma once
// The fleet's status as a text table (fleet/README.md, "The status table"): the
// supervisor's own (each process of its fleet: state, pid, restarts, heartbeat age, state
// and message rate) and `fleet status`'s (every process heard on HEARTBEAT).

#include <cstdint>
#include <string>
#include <vector>

#include "common/heartbeat_monitor.h"
#include "fleet/supervisor.h"

namespace minenav {

// Columns left-aligned to their widest cell, two spaces apart, a header line, one line a row.
std::string FormatTable(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

// process, group, state, pid, restarts, heartbeat age, heartbeat state, messages/s, message.
std::string FleetStatusTable(const std::vector<ProcessStatus>& rows, int64_t now);

// process[:instance], pid, heartbeat age, state, messages/s, bad, message: every process
// whose HEARTBEAT was heard.
std::string BusStatusTable(const HeartbeatMonitor& heartbeats, int64_t now);

}  // namespace minenav
