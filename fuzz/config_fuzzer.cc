// Fuzz target: the config-file parser (common/config.h ConfigSchema::LoadText, what --config FILE
// and the mapper's presets go through) on the widest schema of the fleet: the contour mapper's
// (the runtime's common options, the mapper's nested options with numbers, integers, booleans,
// choices, durations and channels, the flat aliases). A file it accepts must give a
// configuration (--print-config's text) that reads back to the same configuration.

#include <string>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/node_runtime.h"
#include "fuzz/finding.h"
#include "mapper/contour_mapper_node.h"

namespace {

// The effective configuration after `text` (throws UsageError / InputError like the process).
std::string ConfigAfter(const std::string& text, const std::string& source) {
  using namespace minenav;
  ConfigSchema schema("contour_mapper", "fuzz");
  NodeRuntime runtime("contour_mapper", schema);
  ContourMapperNodeOptions options;
  DeclareOptions(OptionScope(schema), options);
  schema.LoadText(text, source);
  return schema.ConfigText();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace minenav;
  SetLogLevel(LogLevel::kError);
  std::string once;
  try {
    once = ConfigAfter(std::string(reinterpret_cast<const char*>(data), size), "fuzz");
  } catch (const UsageError&) {
    return 0;
  } catch (const InputError&) {
    return 0;
  }
  std::string twice;
  try {
    twice = ConfigAfter(once, "round trip");
  } catch (const std::exception& e) {
    fuzz::Fail(std::string("the configuration printed after an accepted file does not read back: ") + e.what());
  }
  if (twice != once) fuzz::Fail("the configuration changes when read back:\n" + once + "\n---\n" + twice);
  return 0;
}
