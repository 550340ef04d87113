// log_tool: make, inspect, export and draw LCM logs of MINENAV runs (logger/README.md).
//   log_tool survey | generate | info | export | render | record | import-carmen | relations |
//            mission-report | spy | export-mcap  [--help]

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "logger/log_tool_commands.h"

namespace {

constexpr const char* kOverview =
    "Usage: log_tool SUBCOMMAND [options]   (log_tool SUBCOMMAND --help for its options)\n"
    "\n"
    "Make, inspect, export and draw LCM event logs of MINENAV runs.\n"
    "\n"
    "Subcommands:\n"
    "  survey    simulate a ladar survey offline (world JSON + stations CSV) into a log\n"
    "            with LADAR_SCAN, ODOMETRY (initial estimates) and SIM_TRUTH, plus truth CSV\n"
    "  generate  write a generated world (mine, mockup, research mine, loop) and stations\n"
    "  info      channels, counts, rates, times, decode errors and sequence gaps of a log\n"
    "  export    poses of a channel to a poses CSV; scans to a scans CSV\n"
    "  render    an SVG of world, map, scans at their poses and trajectories\n"
    "  record    record the bus into a log without dropping bursts (record.sh --engine log_tool)\n"
    "  import-carmen  a CARMEN log (.clf[.gz|.bz2]: Intel, fr079, MIT CSAIL, ...) into an LCM log\n"
    "            with LADAR_SCAN and ODOMETRY\n"
    "  relations score robot poses against a relations file (Kuemmerle 2009, metricEvaluator)\n"
    "  mission-report  judge a finished mission (log, true world, final map, coordinator's report):\n"
    "            a report (Markdown), every figure (JSON), a picture (SVG, PNG)\n"
    "  spy       a terminal spy of the bus (or of a log): rates, sizes, bad messages, decoded fields\n"
    "  join      one log from the parts of a recording (a restarted logger's parts), torn ends dropped\n"
    "  export-mcap  an LCM log as MCAP (JSON channels, Foxglove schemas) for Foxglove and Lichtblick\n"
    "\n"
    "Exit codes: 0 ok, 2 bad flags or input (one line on stderr, no output file written),\n"
    "3 failure while running.\n";

}  // namespace

int main(int argc, char** argv) {
  minenav::SetLogProgramName("log_tool");
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    std::fputs(kOverview, stderr);
    return minenav::kExitUsage;
  }
  const std::string sub = args.front();
  args.erase(args.begin());
  if (sub == "--help" || sub == "-h" || sub == "help") {
    std::fputs(kOverview, stdout);
    return 0;
  }
  try {
    if (sub == "survey") return minenav::RunSurveyCommand(args);
    if (sub == "generate" || sub == "world") return minenav::RunGenerateCommand(args);
    if (sub == "info") return minenav::RunInfoCommand(args);
    if (sub == "export") return minenav::RunExportCommand(args);
    if (sub == "render") return minenav::RunRenderCommand(args);
    if (sub == "record") return minenav::RunRecordCommand(args);
    if (sub == "import-carmen") return minenav::RunImportCarmenCommand(args);
    if (sub == "relations") return minenav::RunRelationsCommand(args);
    if (sub == "mission-report") return minenav::RunMissionReportCommand(args);
    if (sub == "spy") return minenav::RunSpyCommand(args);
    if (sub == "export-mcap") return minenav::RunExportMcapCommand(args);
    if (sub == "join") return minenav::RunJoinCommand(args);
    std::fprintf(stderr, "log_tool: error: unknown subcommand '%s' (see log_tool --help)\n", sub.c_str());
    return minenav::kExitUsage;
  } catch (const minenav::UsageError& e) {
    std::fprintf(stderr, "log_tool %s: error: %s\n", sub.c_str(), e.what());
    return minenav::kExitUsage;
  } catch (const minenav::InputError& e) {
    std::fprintf(stderr, "log_tool %s: error: %s\n", sub.c_str(), e.what());
    return minenav::kExitUsage;
  } catch (const std::invalid_argument& e) {
    // Option validation in the simulator libraries (bad sensor or world parameters).
    std::fprintf(stderr, "log_tool %s: error: %s\n", sub.c_str(), e.what());
    return minenav::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "log_tool %s: failed: %s\n", sub.c_str(), e.what());
    return minenav::kExitRuntime;
  }
}
