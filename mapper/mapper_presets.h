#pragma once
// What configures a contour-mapper run beyond where its input and output go, and the option
// sets shipped for it (presets). A preset is a file of `key = value` lines,
// mapper/presets/NAME.conf, compiled into the binary at build time (cmake/MinenavEmbedText.cmake)
// and loaded as a layer: defaults < preset < --config FILE < flags. The contour_mapper
// process, bench/mapper_carmen_bench.cc and mapper/carmen_regression_test.cc all load a
// preset through LoadMapperPreset, so what the CI slice checks is what the benchmark reports.
//
//   ConfigSchema schema("tool", "...");
//   MapperRunOptions run;
//   DeclareOptions(OptionScope(schema), run);     // insert_min_translation, mapper.pose.final_threshold, ...
//   LoadMapperPreset(schema, "carmen");           // before Parse: --config and flags override it
//
// Plain C++, no LCM.

#include <string>
#include <vector>

#include "common/config.h"
#include "mapper/mapping_session.h"

namespace minenav::mapper {

// A run bounds each concurrent refinement to 10 rounds (the library's 20 suits offline
// benches; the contour_mapper process has always used 10, at the end and periodically).
inline MappingSessionOptions DefaultRunSessionOptions() {
  MappingSessionOptions o;
  o.mapper.refinement.max_rounds = 10;
  return o;
}

struct MapperRunOptions {
  // The policy and every option of the map-building cycle (keys at the scope itself and
  // under `mapper.`).
  MappingSessionOptions session = DefaultRunSessionOptions();
  // Rounds of the concurrent refinement after the last scan; 0 = none.
  int final_refinement_rounds = 10;
  // s; farthest odometry reading from a scan's utime that may serve for it.
  double max_odometry_gap = 1.0;
};

// Declares every field of `o` under `scope`: the session's (DeclareOptions of
// MappingSessionOptions), final_refinement_rounds and max_odometry_gap.
void DeclareOptions(OptionScope scope, MapperRunOptions& o);
std::string ValidateOptions(const MapperRunOptions& o);

// The presets shipped, the default first: "survey", "carmen".
std::vector<std::string> MapperPresetNames();
// The text of mapper/presets/NAME.conf as compiled in. Throws UsageError naming the presets
// for an unknown name.
const std::string& MapperPresetText(const std::string& name);
// Loads preset `name` into `schema`, whose keys must include MapperRunOptions' at the root
// (DeclareOptions above): call it after declaring and before Parse. Errors name the line
// ("preset carmen:42: ...").
void LoadMapperPreset(ConfigSchema& schema, const std::string& name);
// The run options of preset `name` over the defaults, validated (benches and tests that
// have no schema of their own for them).
MapperRunOptions MapperPresetOptions(const std::string& name);

}  // namespace minenav::mapper
