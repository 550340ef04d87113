#include "mapper/mapper_presets.h"

#include <map>

#include "mapper/mapper_presets_text.h"  // generated: kEmbeddedTexts, the files of mapper/presets/

namespace minenav::mapper {

void DeclareOptions(OptionScope s, MapperRunOptions& o) {
  DeclareOptions(s, o.session);
  s.AddInt("final_refinement_rounds", &o.final_refinement_rounds,
           "concurrent refinement rounds after the last scan (4.7; 0 = none); 10 bounds a survey's final "
           "refinement (it usually stops after a few, when a round no longer lowers the total error) [rounds]",
           0, 1000);
  s.AddDouble("max_odometry_gap", &o.max_odometry_gap, "s",
              "farthest odometry reading from a scan's utime that may serve for it (a scan without one is "
              "answered and skipped); 1 s: a reading farther off says little about where the scan was taken, "
              "but a stream that pauses (Intel's ODOM, up to 2.3 s) needs more",
              0.0, 3600.0);
}

std::string ValidateOptions(const MapperRunOptions& o) {
  if (std::string why = ValidateOptions(o.session); !why.empty()) return why;
  if (o.final_refinement_rounds < 0) return "final_refinement_rounds must be >= 0";
  if (!(o.max_odometry_gap >= 0.0)) return "max_odometry_gap must be >= 0 s";
  return "";
}

namespace {

const std::map<std::string, std::string>& Presets() {
  static const std::map<std::string, std::string> presets = [] {
    std::map<std::string, std::string> out;
    for (const embedded::EmbeddedText& t : embedded::kEmbeddedTexts) out.emplace(t.name, t.text);
    return out;
  }();
  return presets;
}

}  // namespace

std::vector<std::string> MapperPresetNames() {
  std::vector<std::string> names;
  for (const embedded::EmbeddedText& t : embedded::kEmbeddedTexts) names.emplace_back(t.name);
  return names;
}

const std::string& MapperPresetText(const std::string& name) {
  const auto found = Presets().find(name);
  if (found == Presets().end()) {
    std::string list;
    for (const std::string& n : MapperPresetNames()) list += (list.empty() ? "" : ", ") + n;
    throw UsageError("--preset must be one of " + list + ", got '" + name + "'");
  }
  return found->second;
}

void LoadMapperPreset(ConfigSchema& schema, const std::string& name) {
  schema.LoadText(MapperPresetText(name), "preset " + name);
}

MapperRunOptions MapperPresetOptions(const std::string& name) {
  MapperRunOptions o;
  ConfigSchema schema("preset " + name, "");
  DeclareOptions(OptionScope(schema), o);
  LoadMapperPreset(schema, name);
  if (const std::string why = ValidateOptions(o); !why.empty()) throw UsageError("preset " + name + ": " + why);
  return o;
}

}  // namespace minenav::mapper
