// Fuzz target: the fleet file parser (fleet/fleet_file.h ParseFleetFile) with the built-in
// variables `fleet run` gives it, then what `fleet run` does with an accepted file before it
// starts anything: the start order and each host group's selection.

#include <string>

#include "common/file_io.h"
#include "fleet/fleet_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::map<std::string, std::string> builtins = {
      {kOutVariable, "/tmp/out"}, {kBinVariable, "/opt/minenav/bin"}, {kFleetDirVariable, "/etc/minenav"}};
  try {
    const FleetSpec fleet = ParseFleetFile(text, "fuzz.fleet", builtins, {});
    (void)StartOrder(fleet);
    for (const std::string& group : fleet.Groups()) (void)StartOrder(SelectGroups(fleet, {group}));
    for (const ProcessSpec& p : fleet.processes) (void)QuoteCommand(p.argv);
  } catch (const InputError&) {
  }
  return 0;
}
