// log_tool import-carmen: a CARMEN log (the Radish / Freiburg benchmark logs) into an LCM
// event log of LADAR_SCAN and ODOMETRY messages, which the ladar driver replays live
// (--replay) and every process reads in batch (--log). Parsing is carmen_log.h.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "common/config.h"
#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "dataset_readers/carmen_log.h"
#include "logger/log_tool_commands.h"

namespace minenav {

int RunImportCarmenCommand(const std::vector<std::string>& raw_args) {
  const std::vector<std::string> args = ExpandBareBoolFlags(raw_args, {"monotonic_times"});
  std::string scan_channel = "LADAR_SCAN", odometry_channel = "ODOMETRY", scan_odometry = "auto";
  CarmenReadOptions read;
  ConfigSchema schema(
      "log_tool import-carmen",
      "Converts a CARMEN log (.clf, .clf.gz, .clf.bz2, .log.gz) into an LCM event log: FLASER and\n"
      "ROBOTLASER1 lines become ladar_scan_t on LADAR_SCAN (utime = ipc timestamp, the laser's\n"
      "offset from the robot in sensor_offset, no-return readings NaN), ODOM lines odometry_t on\n"
      "ODOMETRY. Messages keep the file's order within each stream; the two streams are merged by\n"
      "time. Event timestamps never go backwards (Intel's ipc times do: such events are stamped with\n"
      "the previous event's time; the message utime stays the raw ipc time unless\n"
      "--monotonic-times). Progress on stderr. Writes OUT.partial and renames it at the end.");
  schema.SetPositional("IN OUT", 2, 2);
  schema.AddString("scan_channel", &scan_channel, "channel for the scans");
  schema.AddString("odometry_channel", &odometry_channel, "channel for the odometry");
  schema.AddString("scan_odometry", &scan_odometry,
                   "publish each laser line's robot pose on the odometry channel: auto (only when the log has\n"
                   "no ODOM lines, e.g. mit-csail), always, never");
  schema.AddDouble("max_range", &read.max_range, "m",
                   "upper bound on a scan's maximum range; readings at or beyond it are no return", 0.1, 1000.0);
  schema.AddDouble("min_range", &read.min_range, "m", "readings below this are no return", 0.0, 1000.0);
  schema.AddBool("monotonic_times", &read.monotonic_times,
                 "make message utimes strictly increasing per stream (then they no longer match the\n"
                 "relations files for the reordered scans)");
  schema.AddHelpEpilog("Example: log_tool import-carmen intel.clf.bz2 intel.lcm\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  if (scan_odometry != "auto" && scan_odometry != "always" && scan_odometry != "never")
    throw UsageError("--scan-odometry must be auto, always or never, got '" + scan_odometry + "'");
  if (scan_channel.empty() || odometry_channel.empty()) throw UsageError("channel names must not be empty");
  if (read.min_range >= read.max_range) throw UsageError("--min-range must be below --max-range");
  const std::string in = schema.positional()[0];
  const std::string out = schema.positional()[1];
  CheckOutputIsNotInput("OUT", out, {in});
  // The log is written as OUT.partial first: that must not be the input either.
  CheckOutputIsNotInput("OUT (written first as OUT.partial)", out + ".partial", {in});

  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // Progress starts once the input is known good, so a bad input gives one line only.
  const CarmenLog log = ReadCarmenLog(in, read);
  const CarmenLogStats& st = log.stats;
  if (log.scans.empty()) throw InputError(in + ": no FLASER or ROBOTLASER1 lines");
  std::fprintf(stderr,
               "log_tool import-carmen: %lld lines: %lld FLASER, %lld ROBOTLASER1, %lld ODOM, %lld PARAM, "
               "%lld other, read in %.1f s\n",
               static_cast<long long>(st.lines), static_cast<long long>(st.flaser_lines),
               static_cast<long long>(st.robotlaser1_lines), static_cast<long long>(st.odom_lines),
               static_cast<long long>(st.param_lines), static_cast<long long>(st.ignored_lines), seconds());

  const bool laser_odometry = scan_odometry == "always" || (scan_odometry == "auto" && log.odometry.empty());
  std::vector<OdometryReading> odometry = log.odometry;
  if (laser_odometry) {
    if (!odometry.empty()) {
      // Both kinds in one stream, each in file order, merged by time below.
      std::vector<OdometryReading> merged;
      merged.reserve(odometry.size() + log.scan_odometry.size());
      size_t a = 0, b = 0;
      while (a < odometry.size() || b < log.scan_odometry.size()) {
        const bool take_a = b >= log.scan_odometry.size() ||
                            (a < odometry.size() && odometry[a].utime <= log.scan_odometry[b].utime);
        merged.push_back(take_a ? odometry[a++] : log.scan_odometry[b++]);
      }
      odometry = std::move(merged);
    } else {
      odometry = log.scan_odometry;
    }
    for (size_t i = 0; i < odometry.size(); ++i) odometry[i].seq = static_cast<int64_t>(i);
  }

  LogWriter writer(out);
  const size_t total = log.scans.size() + odometry.size();
  size_t s = 0, o = 0, written = 0, next_report = total / 10;
  int64_t event_time = std::numeric_limits<int64_t>::min();
  int64_t clamped = 0;
  while (s < log.scans.size() || o < odometry.size()) {
    // Odometry first on equal times, so a consumer has it when the scan arrives.
    const bool take_scan =
        o >= odometry.size() || (s < log.scans.size() && log.scans[s].utime < odometry[o].utime);
    const int64_t utime = take_scan ? log.scans[s].utime : odometry[o].utime;
    if (utime < event_time) ++clamped;
    event_time = std::max(event_time, utime);
    if (take_scan) {
      writer.WriteMessage(scan_channel, event_time, ToLcm(log.scans[s++]));
    } else {
      writer.WriteMessage(odometry_channel, event_time, ToLcm(odometry[o++]));
    }
    if (++written >= next_report && total >= 10) {
      std::fprintf(stderr, "log_tool import-carmen: %3.0f %%  %zu events (%.1f s)\n",
                   100.0 * static_cast<double>(written) / static_cast<double>(total), written, seconds());
      next_report += total / 10;
    }
  }
  writer.Close();
  const int64_t bytes = static_cast<int64_t>(std::filesystem::file_size(out));
  const double duration = static_cast<double>(log.scans.back().utime - log.scans.front().utime) * 1e-6;
  std::fprintf(stderr,
               "log_tool import-carmen: %zu scans on %s, %zu odometry on %s%s, %.0f s of data; %lld events "
               "stamped with an earlier event's time (ipc time went backwards); %lld no-return readings; "
               "%lld bytes in %.1f s -> %s\n",
               log.scans.size(), scan_channel.c_str(), odometry.size(), odometry_channel.c_str(),
               laser_odometry ? " (laser-line robot poses)" : "", duration, static_cast<long long>(clamped),
               static_cast<long long>(st.no_return_readings), static_cast<long long>(bytes), seconds(), out.c_str());
  std::printf("%s\n", out.c_str());
  return 0;
}

}  // namespace minenav
