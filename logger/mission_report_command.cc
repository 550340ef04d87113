// log_tool mission-report: judges a finished mission from what it left behind (its log, the
// true world, the final contour map, the coordinator's report) and writes the report
// (Markdown), every figure (JSON) and the picture (SVG, and PNG through rsvg-convert).
// The figures are evaluation/mission_evaluation.h's; this file reads the inputs and writes.

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/auth_key_file.h"
#include "common/config.h"
#include "common/file_io.h"
#include "evaluation/mission_evaluation.h"
#include "evaluation/mission_picture.h"
#include "logger/log_tool_commands.h"
#include "logger/mission_log.h"
#include "mapper/contour_map_io.h"
#include "common/child_process.h"

namespace minenav {

namespace {

// The program's path when it is an executable file on PATH, else "".
std::string FindOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, end - start);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return "";
}

constexpr const char* kSvgToPng = "rsvg-convert";

// SVG file -> PNG file of the SVG's own size (rsvg-convert, Debian's librsvg2-bin). Written to
// a temporary name, checked to be a PNG, renamed.
void ConvertSvgToPng(const std::string& converter, const std::string& svg_path, const std::string& png_path) {
  const std::string tmp = png_path + ".tmp." + std::to_string(::getpid()) + ".png";
  const std::string output = tmp + ".log";
  const ProgramRun run = RunProgram(converter, {"--format=png", "-o", tmp, svg_path}, output, 120.0);
  std::error_code ignored;
  std::filesystem::remove(output, ignored);
  const std::string png = ReadFile(tmp);
  if (run.exit_code != 0 || png.size() < 24 || png.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) {
    std::filesystem::remove(tmp, ignored);
    std::string why = run.output.substr(0, run.output.find('\n'));
    throw std::runtime_error(std::string(kSvgToPng) + " did not make a PNG of " + svg_path + " (exit " +
                             std::to_string(run.exit_code) + (why.empty() ? "" : ": " + why) + ")");
  }
  std::filesystem::rename(tmp, png_path);
}

mapper::ContourMap MapFromMessage(const ContourMapMessage& m) {
  mapper::ContourMap map;
  for (const ContourPolyline& c : m.contours)
    if (c.points.size() >= (c.closed ? 3u : 2u)) map.Create(c.points, c.closed);
  return map;
}

}  // namespace

int RunMissionReportCommand(const std::vector<std::string>& raw_args) {
  std::vector<std::string> args = raw_args;
  std::vector<std::string> notes = TakeRepeatedFlag(&args, "note");
  std::string log_path, world_path, map_path, mission_path;
  std::string report_out, json_out, svg_out, png_out;
  MissionEvaluationOptions options;
  MissionPictureOptions picture;
  MissionLogChannels channels;
  ConfigSchema schema(
      "log_tool mission-report",
      "Judges a finished mission from what it left behind and writes a short report (Markdown), every\n"
      "figure (JSON) and a picture (SVG, PNG): explored area and time, map accuracy against the true\n"
      "world, pose error along the drive (POSE and ODOMETRY against SIM_TRUTH), the depth of each cut\n"
      "against the request, planning times, and what was retried or refused (evaluation/README.md,\n"
      "\"Mission report\", says how each figure is computed).");
  schema.AddString("log", &log_path, "the mission's LCM log (required)");
  schema.AddString("world", &world_path,
                   "the true world at the start (segments JSON); without it the log's first SIM_WORLD");
  schema.AddString("map", &map_path, "the final contour map (contour-map JSON); without it the log's last CONTOUR_MAP");
  schema.AddString("mission", &mission_path, "the coordinator's report (--report-out JSON); without it no per-cut section");
  schema.AddString("report_out", &report_out, "the report to write (Markdown)");
  schema.AddString("json_out", &json_out, "every figure as JSON");
  schema.AddString("svg_out", &svg_out, "the picture (SVG)");
  schema.AddString("png_out", &png_out, "the picture (PNG, through rsvg-convert of Debian's librsvg2-bin)");
  std::string note_help;  // --note is taken out above; listed here for --help
  schema.AddString("note", &note_help, "a line to add to the report and the picture (repeat for several), e.g. the run's speed");
  schema.AddString("title", &picture.title, "the picture's title");
  std::string key_file;
  schema.AddString("key_file", &key_file,
                   "the fleet's key file (run_demo.sh's OUT/fleet.key): messages on the signed channels that do not\n"
                   "verify (an attacker's) are counted and not used; without it every message is read");
  DeclareOptions(OptionScope(schema), options);
  const OptionScope ch = OptionScope(schema).Nested("channel");
  ch.AddString("truth", &channels.truth, "channel of the true poses (vehicle_truth_t)");
  ch.AddString("pose", &channels.pose, "channel of the fleet's estimates (pose_estimate_t)");
  ch.AddString("odometry", &channels.odometry, "channel of the dead reckoning (odometry_t)");
  ch.AddString("world", &channels.world, "channel of the true world (line_map_t)");
  ch.AddString("path", &channels.path, "channel of the planner's answers (path_t)");
  ch.AddString("drive_path", &channels.drive_path, "channel of the paths sent to the tracker (path_t)");
  ch.AddString("contour_map", &channels.contour_map, "channel of the contour map (contour_map_t)");
  schema.AddHelpEpilog(
      "Example: log_tool mission-report --log OUT/mission.lcm --world OUT/mine.json --map OUT/contour_map.json\n"
      "         --mission OUT/mission.json --report-out OUT/report.md --json-out OUT/report.json\n"
      "         --svg-out OUT/mission.svg --png-out OUT/mission.png\n"
      "Exit codes: 0 ok; 2 bad flags or input (one line, nothing written); 3 the PNG could not be made\n"
      "(rsvg-convert missing: nothing written; failed: the other outputs are written).\n");
  if (schema.Parse(args) == ParseOutcome::kExit) return 0;
  RequireOutputPath(log_path, "--log");
  if (report_out.empty() && json_out.empty() && svg_out.empty() && png_out.empty())
    throw UsageError("nothing to write: give --report-out, --json-out, --svg-out and/or --png-out");
  if (options.cut.inner_from >= options.cut.inner_to)
    throw UsageError("--cut.inner-from must be less than --cut.inner-to");
  const std::vector<std::string> inputs = {log_path, world_path, map_path, mission_path};
  for (const auto& [flag, out] : {std::pair<const char*, std::string>{"--report-out", report_out},
                                  {"--json-out", json_out}, {"--svg-out", svg_out}, {"--png-out", png_out}})
    CheckOutputIsNotInput(flag, out, inputs);
  std::string converter;
  if (!png_out.empty()) {
    converter = FindOnPath(kSvgToPng);
    if (converter.empty())
      throw std::runtime_error(std::string(kSvgToPng) +
                               " not found on PATH, so no PNG: install Debian's librsvg2-bin (scripts/common.sh "
                               "installs it: source scripts/common.sh; minenav_install_deps)");
  }

  std::optional<MissionLogAuth> auth;
  if (!key_file.empty()) auth = MissionLogAuth{LoadAuthKeyFile(key_file)};
  MissionLog log = ReadMissionLog(log_path, channels, auth ? &*auth : nullptr);
  MissionInputs in;
  in.log = std::move(log.record);
  in.notes = notes;
  const std::vector<WorldSnapshot>& worlds = in.log.worlds;
  if (!world_path.empty()) {
    in.initial_world = LoadSegmentsJson(world_path);
    in.world_source = "at the start: " + world_path;
    if (!worlds.empty() && !SameSegments(worlds.front().segments, in.initial_world))
      in.world_source += " (the log's first SIM_WORLD differs from it)";
  } else if (!worlds.empty()) {
    in.initial_world = worlds.front().segments;
    in.world_source = "at the start: the log's first SIM_WORLD (version " + std::to_string(worlds.front().version) + ")";
  } else {
    throw InputError(log_path + ": no SIM_WORLD in the log: give the true world with --world");
  }
  if (!worlds.empty()) {
    in.final_world = worlds.back().segments;
    in.world_source += "; at the end: the log's last SIM_WORLD (version " + std::to_string(worlds.back().version) +
                       ", " + std::to_string(worlds.size()) + " SIM_WORLD messages)";
  } else {
    in.final_world = in.initial_world;
    in.world_source += "; no SIM_WORLD in the log: the world at the end taken to be the same";
  }
  if (!map_path.empty()) {
    in.map = mapper::LoadContourMapJson(map_path);
    in.map_source = map_path;
  } else if (log.last_contour_map) {
    in.map = MapFromMessage(*log.last_contour_map);
    in.map_source = "the log's last CONTOUR_MAP (version " + std::to_string(log.last_contour_map->version) + ")";
  } else {
    throw InputError(log_path + ": no CONTOUR_MAP in the log: give the final map with --map");
  }
  if (!mission_path.empty()) in.mission = ParseMissionReportJson(ReadFile(mission_path), mission_path);

  const MissionFigures figures = EvaluateMission(in, options);
  if (!json_out.empty()) WriteFileAtomically(json_out, MissionFiguresToJson(in, figures, options));
  if (!report_out.empty()) WriteFileAtomically(report_out, MissionReportMarkdown(in, figures, options));
  if (!svg_out.empty() || !png_out.empty()) {
    const std::string svg = RenderSvg(MissionScene(in, figures, options, picture), picture.render);
    const std::string svg_path = svg_out.empty() ? png_out + ".tmp." + std::to_string(::getpid()) + ".svg" : svg_out;
    WriteFileAtomically(svg_path, svg);
    if (!png_out.empty()) {
      try {
        ConvertSvgToPng(converter, svg_path, png_out);
      } catch (...) {
        if (svg_out.empty()) std::filesystem::remove(svg_path);
        throw;
      }
      if (svg_out.empty()) std::filesystem::remove(svg_path);
    }
  }
  for (const std::string& line : HeadlineLines(in, figures)) std::fprintf(stderr, "log_tool mission-report: %s\n", line.c_str());
  if (in.log.bad_messages > 0)
    std::fprintf(stderr, "log_tool mission-report: %lld messages skipped (first: %s)\n",
                 static_cast<long long>(in.log.bad_messages), in.log.first_bad.c_str());
  if (in.log.auth_refused > 0)
    std::fprintf(stderr, "log_tool mission-report: %lld messages refused by authentication, not used (first: %s)\n",
                 static_cast<long long>(in.log.auth_refused), in.log.first_auth_refused.c_str());
  if (!in.log.damage.empty())
    std::fprintf(stderr, "log_tool mission-report: the log is damaged (%s): the report is made from what came before\n",
                 in.log.damage.c_str());
  return 0;
}

}  // namespace minenav
