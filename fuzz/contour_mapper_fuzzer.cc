// Fuzz target: contour_mapper's handlers (mapper/contour_mapper_node.h) with hostile LADAR_SCAN
// and ODOMETRY (fuzz/node_fuzz.h), its options those of the process (the survey preset), in
// batch (the node maps each scan as it is read then; live, the same session runs on a worker
// thread): every POSE and CONTOUR_MAP it sends must be one its receivers accept. The final
// refinement of a batch run (end of the log, not a handler) is off: it costs seconds an input.

#include <stdexcept>
#include <string>

#include "common/file_io.h"
#include "fuzz/mapper_process_options.h"
#include "fuzz/node_fuzz.h"
#include "mapper/contour_mapper_node.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  static const ContourMapperNodeOptions options = [] {
    ContourMapperNodeOptions o = fuzz::MapperProcessDefaults();
    o.run.final_refinement_rounds = 0;
    return o;
  }();
  const auto h = fuzz::NodeFuzzHarness::Batch("contour_mapper", data, size, {"LADAR_SCAN", "ODOMETRY"});
  h->ExpectOutput<pose_estimate_t>("POSE");
  h->ExpectOutput<contour_map_t>("CONTOUR_MAP");
  h->ExpectOutput<heartbeat_t>("HEARTBEAT");
  ContourMapperNode node(h->runtime(), options, OpenMappingSession(options));
  try {
    node.Run();
  } catch (const InputError&) {
    // A log without a scan: `contour_mapper --log` exits 2 with this line.
  } catch (const std::runtime_error& e) {
    // A log none of whose scans could be inserted (each refused: too few points, no pose):
    // `contour_mapper --log` exits 3 with this line. Anything else is a finding.
    if (std::string(e.what()) != "no scan could be inserted") throw;
  }
  return 0;
}
