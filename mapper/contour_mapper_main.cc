// contour_mapper (thesis chapter 4, CLUE) as a process of the fleet: its options and the
// wiring of ContourMapperNode (mapper/contour_mapper_node.h, which says what it does).
//
// Batch (--log IN.lcm --map-out MAP.json [--poses-out POSES.csv] [--svg-out MAP.svg]):
// reads the log's LADAR_SCAN and ODOMETRY in file order, as fast as it can, maps every
// scan, runs a final concurrent refinement (4.7) and writes the contour-map JSON, one pose
// per inserted or tracked scan and a picture. Tools outside the project call exactly this.
// Live (no --log): maps each scan as it arrives and publishes POSE per scan and CONTOUR_MAP
// whenever the map changed, plus HEARTBEAT.
//
// Options: the node's (files, channels, queue), the run's (insert_min_translation, ...,
// final_refinement_rounds, max_odometry_gap) and every option of the mapper library under
// mapper. (mapper.pose.final_threshold, ...; mapper/README.md has the table, which
// --print-options-table prints). Precedence: defaults < --preset (mapper/presets/NAME.conf,
// compiled in) < --config FILE < flags. Exit codes: 0 ok, 2 bad flag or input file (or an
// output naming an input), 3 runtime failure, 130 a batch run stopped by SIGINT/SIGTERM.

#include <string>
#include <utility>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "mapper/contour_mapper_node.h"
#include "mapper/mapper_presets.h"

namespace minenav {
namespace {

constexpr const char* kHelpEpilog =
    "Examples:\n"
    "  contour_mapper --log survey.lcm --map-out map.json --poses-out poses.csv --svg-out map.svg   (batch)\n"
    "  contour_mapper --checkpoint run.ckpt --checkpoint-every 10 --save-map map.json                 (live)\n"
    "Exit codes: 0 ok, 2 bad flag or input file (or an output naming an input), 3 runtime failure,\n"
    "130 batch run stopped by SIGINT/SIGTERM (what was done is in MAP.partial, POSES.partial, SVG.partial).\n"
    "A second SIGINT/SIGTERM ends the process at once (the checkpoint is saved before the final refinement).\n";

int Main(int argc, char** argv) {
  ConfigSchema schema("contour_mapper",
                      "Contour mapper (thesis ch. 4, CLUE): LADAR_SCAN + ODOMETRY -> contour map (CONTOUR_MAP), "
                      "poses (POSE); batch over a log with --log.");
  NodeRuntime runtime("contour_mapper", schema);
  // The preset is the layer between the defaults and --config/flags, so it is read first,
  // from the command line or the config file (what --print-config shows is in force).
  std::string preset = PeekOption(argc, argv, "preset").value_or("survey");
  schema.AddString("preset", &preset,
                   "option set the other options start from: survey (360-degree scans at stations, thesis 5.2) or\n"
                   "carmen (180-degree SICK scans from a moving robot: the public CARMEN logs, imported with\n"
                   "log_tool import-carmen); mapper/presets/NAME.conf says why each value",
                   mapper::MapperPresetNames());
  ContourMapperNodeOptions options;
  DeclareOptions(OptionScope(schema), options);
  mapper::LoadMapperPreset(schema, preset);
  schema.AddHelpEpilog(kHelpEpilog);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (schema.WasSet("checkpoint_every") && options.checkpoint.empty())
    throw UsageError("--checkpoint-every needs --checkpoint FILE");
  ValidateNodeOptions(options, runtime.options(), PeekOption(argc, argv, "config").value_or(""));

  mapper::MappingSession session = OpenMappingSession(options);
  runtime.Start();
  ContourMapperNode node(runtime, std::move(options), std::move(session));
  return node.Run();
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("contour_mapper", [&] { return minenav::Main(argc, argv); });
}
