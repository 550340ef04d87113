// log_tool info, export and render: commands that read a log.

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "logger/log_render.h"
#include "logger/log_summary.h"
#include "logger/log_tool_commands.h"
#include "logger/run_log.h"

namespace minenav {

std::vector<std::string> TakeRepeatedFlag(std::vector<std::string>* args, const std::string& name) {
  std::vector<std::string> values;
  std::vector<std::string> rest;
  const std::string flag = "--" + name, prefix = flag + "=";
  for (size_t i = 0; i < args->size(); ++i) {
    const std::string& a = (*args)[i];
    if (a == flag) {
      if (i + 1 >= args->size()) throw UsageError(flag + " needs a value");
      values.push_back((*args)[++i]);
    } else if (a.rfind(prefix, 0) == 0) {
      values.push_back(a.substr(prefix.size()));
    } else {
      rest.push_back(a);
    }
  }
  *args = std::move(rest);
  return values;
}

std::vector<std::string> ExpandBareBoolFlags(const std::vector<std::string>& args,
                                             const std::vector<std::string>& bool_flags) {
  const auto is_bool_word = [](const std::string& w) {
    for (const char* b : {"true", "false", "1", "0", "yes", "no", "on", "off"})
      if (w == b) return true;
    return false;
  };
  std::vector<std::string> out;
  for (size_t i = 0; i < args.size(); ++i) {
    bool bare = false;
    for (const auto& f : bool_flags) {
      std::string dashed = f;
      std::replace(dashed.begin(), dashed.end(), '_', '-');
      if (args[i] == "--" + f || args[i] == "--" + dashed) bare = true;
    }
    if (bare && !(i + 1 < args.size() && is_bool_word(args[i + 1]))) out.push_back(args[i] + "=true");
    else out.push_back(args[i]);
  }
  return out;
}

void RequireOutputPath(const std::string& path, const std::string& flag) {
  if (path.empty()) throw UsageError(flag + " is required (see --help)");
}

int RunInfoCommand(const std::vector<std::string>& raw_args) {
  const std::vector<std::string> args = ExpandBareBoolFlags(raw_args, {"json"});
  bool json = false;
  std::string json_out;
  ConfigSchema schema("log_tool info",
                      "Channels, message types (by fingerprint), counts, bytes, rates, first and last time,\n"
                      "decode errors and gaps in seq/scan_id of an LCM event log.");
  schema.SetPositional("LOG", 1, 1);
  schema.AddBool("json", &json, "print JSON instead of the table");
  schema.AddString("json_out", &json_out, "also write the JSON summary to this file");
  schema.AddHelpEpilog(
      "Exit code 2 (after printing the report) when the file is damaged or any message on a\n"
      "channel named in DESIGN.md fails to decode as its type.\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  const std::string path = schema.positional()[0];
  // Before anything is read or written: `info LOG --json-out LOG` replaced the log with JSON.
  CheckOutputIsNotInput("--json-out", json_out, {path});
  const LogSummary summary = SummarizeLog(path);
  const std::string json_text = LogSummaryToJson(summary);
  std::cout << (json ? json_text : FormatLogSummary(summary));
  if (!json_out.empty()) WriteFileAtomically(json_out, json_text);
  if (!summary.file_error.empty()) {
    std::fprintf(stderr, "log_tool info: error: %s\n", summary.file_error.c_str());
    return kExitUsage;
  }
  if (summary.total_decode_errors() > 0) {
    for (const auto& c : summary.channels)
      if (c.decode_errors > 0) {
        std::fprintf(stderr, "log_tool info: error: %lld decode errors; first: %s\n",
                     static_cast<long long>(summary.total_decode_errors()), c.first_error.c_str());
        break;
      }
    return kExitUsage;
  }
  return 0;
}

int RunExportCommand(const std::vector<std::string>& raw_args) {
  const std::vector<std::string> args = ExpandBareBoolFlags(raw_args, {"valid_only"});
  std::string poses_channel, out, scans_out, scan_channel = "LADAR_SCAN";
  bool valid_only = false;
  ConfigSchema schema("log_tool export",
                      "Poses of one channel (ODOMETRY, SIM_TRUTH, POSE*) to a poses CSV (utime,x,y,theta; one\n"
                      "row per message), and/or the scans of a channel to a scans CSV\n"
                      "(utime,scan_id,index,bearing,range; one row per reading).");
  schema.SetPositional("LOG", 1, 1);
  schema.AddString("poses", &poses_channel, "channel whose poses to export (needs --out)");
  schema.AddString("out", &out, "poses CSV to write");
  schema.AddString("scans_out", &scans_out, "scans CSV to write");
  schema.AddString("scan_channel", &scan_channel, "channel of the scans for --scans-out");
  schema.AddBool("valid_only", &valid_only, "scans CSV: only readings that are valid returns");
  schema.AddHelpEpilog("Example: log_tool export survey.lcm --poses SIM_TRUTH --out truth.csv --scans-out scans.csv\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  const std::string path = schema.positional()[0];
  if (poses_channel.empty() && scans_out.empty()) throw UsageError("nothing to export: give --poses CHANNEL --out FILE and/or --scans-out FILE");
  if (!poses_channel.empty()) RequireOutputPath(out, "--out (with --poses)");
  if (poses_channel.empty() && !out.empty()) throw UsageError("--out needs --poses CHANNEL");
  CheckOutputIsNotInput("--out", out, {path});
  CheckOutputIsNotInput("--scans-out", scans_out, {path});

  RunLogOptions read_options;
  read_options.read_scans = !scans_out.empty();
  const RunLog run = ReadRunLog(path, read_options);
  // Check everything before writing anything.
  const PoseTrack* track = nullptr;
  if (!poses_channel.empty()) {
    const auto it = run.tracks.find(poses_channel);
    if (it == run.tracks.end()) {
      std::string list;
      for (const auto& [name, t] : run.tracks) list += (list.empty() ? "" : ", ") + name;
      throw InputError(path + ": no poses on channel " + poses_channel +
                       " (pose channels in the log: " + (list.empty() ? "none" : list) + ")");
    }
    track = &it->second;
  }
  const std::vector<LadarScan>* scans = nullptr;
  if (!scans_out.empty()) {
    const auto it = run.scans.find(scan_channel);
    if (it == run.scans.end()) throw InputError(path + ": no scans on channel " + scan_channel);
    scans = &it->second;
  }
  if (track) {
    SavePosesCsv(out, track->poses);
    std::fprintf(stderr, "log_tool export: %zu poses of %s -> %s\n", track->poses.size(), poses_channel.c_str(),
                 out.c_str());
  }
  if (scans) {
    WriteFileAtomically(scans_out, ScansToCsv(*scans, valid_only));
    std::fprintf(stderr, "log_tool export: %zu scans of %s -> %s\n", scans->size(), scan_channel.c_str(),
                 scans_out.c_str());
  }
  return 0;
}

int RunRenderCommand(const std::vector<std::string>& raw_args) {
  std::vector<std::string> args = ExpandBareBoolFlags(raw_args, {"scans_at_odometry"});
  LogRenderOptions options;
  options.world_paths = TakeRepeatedFlag(&args, "world");
  std::string out;
  SvgRenderOptions svg;
  ConfigSchema schema("log_tool render",
                      "An SVG of a logged run: world walls (--world, may repeat), a map (--map: segments or\n"
                      "contours JSON), scan points at their poses, trajectories of SIM_TRUTH, ODOMETRY and\n"
                      "every POSE* channel, error links truth -> odometry, grid, scale bar and legend.");
  schema.SetPositional("LOG", 1, 1);
  schema.AddString("out", &out, "SVG file to write");
  std::string world_help;  // --world is taken out above; listed here for --help
  schema.AddString("world", &world_help, "world segments JSON to draw (repeat for several)");
  schema.AddString("map", &options.map_path, "map to draw: segments JSON or contour-map JSON");
  schema.AddString("scan_channel", &options.scan_channel, "channel of the scans");
  schema.AddString("truth_channel", &options.truth_channel, "channel of the true poses");
  schema.AddString("odometry_channel", &options.odometry_channel, "channel of the odometry / initial estimates");
  schema.AddString("scans_at", &options.scans_at,
                   "draw scans at: auto (truth, else odometry), truth, odometry, none, or a pose channel");
  schema.AddBool("scans_at_odometry", &options.scans_at_odometry, "also draw scans at odometry poses");
  schema.AddInt("max_points_per_scan", &options.max_points_per_scan,
                "readings drawn per scan, evenly strided (0 = all)", 0);
  schema.AddInt("max_scans", &options.max_scans, "scans drawn, evenly spaced over the log (0 = all)", 0);
  schema.AddInt64("max_pose_gap_us", &options.max_pose_gap_us,
                  "interpolate a scan's pose between poses at most this far apart [us]", 0);
  schema.AddString("title", &options.title, "title (default: the log path)");
  schema.AddDouble("width_px", &svg.width_px, "px", "width of the drawing", 100.0, 20000.0);
  schema.AddDouble("max_height_px", &svg.max_height_px, "px", "maximum height of the drawing", 100.0, 20000.0);
  schema.AddHelpEpilog("Example: log_tool render survey.lcm --world mine.json --out survey.svg\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  RequireOutputPath(out, "--out");
  std::vector<std::string> inputs = options.world_paths;
  inputs.push_back(schema.positional()[0]);
  inputs.push_back(options.map_path);
  CheckOutputIsNotInput("--out", out, inputs);
  const LogRenderResult result = BuildLogScene(schema.positional()[0], options);
  WriteFileAtomically(out, RenderSvg(result.scene, svg));
  std::fprintf(stderr, "log_tool render: %d scans drawn (%d without a pose) -> %s\n", result.scans_drawn,
               result.scans_without_pose, out.c_str());
  return 0;
}

}  // namespace minenav
