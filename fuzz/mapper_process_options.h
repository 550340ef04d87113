#pragma once
// The options `contour_mapper` runs with when given no flags (its survey preset), for the two
// fuzz targets that run the mapper's code as the process does (node and checkpoint).

#include <string>
#include <vector>

#include "common/config.h"
#include "mapper/contour_mapper_node.h"
#include "mapper/mapper_presets.h"

namespace minenav::fuzz {

inline ContourMapperNodeOptions MapperProcessDefaults() {
  ConfigSchema schema("contour_mapper", "fuzz");
  ContourMapperNodeOptions options;
  DeclareOptions(OptionScope(schema), options);
  mapper::LoadMapperPreset(schema, "survey");
  schema.Parse(std::vector<std::string>{});
  return options;
}

}  // namespace minenav::fuzz
