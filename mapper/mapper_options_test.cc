// The mapper's options as data (issue 12): every field of every options struct is declared
// (a new field without a declaration fails FieldsAreAllDeclared), each key reaches its own
// field and no other, and the presets shipped as mapper/presets/*.conf give exactly the
// values the C++ preset they replaced gave, bit for bit.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/config.h"
#include "mapper/mapper_presets.h"
#include "mapper/mapping_session.h"

namespace minenav::mapper {
namespace {

// Counts the fields of an aggregate: the most initializers `T{...}` accepts. Each initializer
// converts to any field type, nested options structs included (one initializer each).
struct AnyField {
  template <typename T>
  operator T() const;  // never defined: only used in unevaluated braces
};

template <typename T, typename... Fields>
constexpr size_t FieldCount() {
  if constexpr (requires { T{Fields{}..., AnyField{}}; })
    return FieldCount<T, Fields..., AnyField>();
  else
    return sizeof...(Fields);
}

// The keys DeclareOptions declares for a default T, with their printed values, in order.
template <typename T>
std::vector<std::pair<std::string, std::string>> DeclaredKeys() {
  T o{};
  ConfigSchema schema("test", "");
  DeclareOptions(OptionScope(schema), o);
  std::vector<std::pair<std::string, std::string>> keys;
  std::istringstream text(schema.ConfigText());
  for (std::string line; std::getline(text, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find(" = ");
    keys.emplace_back(line.substr(0, eq), line.substr(eq + 3));
  }
  return keys;
}

template <typename T>
size_t KeyCount() {
  return DeclaredKeys<T>().size();
}

// A leaf struct (no nested options) declares one key per field; a composite one one key per
// plain field plus the keys of each nested struct. When a field is added, FieldCount grows
// and these fail until DeclareOptions declares it.
TEST(MapperOptionsTest, FieldsAreAllDeclared) {
  EXPECT_EQ(KeyCount<ScanPreprocessingOptions>(), FieldCount<ScanPreprocessingOptions>());
  EXPECT_EQ(KeyCount<PoseEstimationOptions>(), FieldCount<PoseEstimationOptions>());
  EXPECT_EQ(KeyCount<MapExpansionOptions>(), FieldCount<MapExpansionOptions>());
  EXPECT_EQ(KeyCount<MapDisappearanceOptions>(), FieldCount<MapDisappearanceOptions>());
  EXPECT_EQ(KeyCount<ContourFittingOptions>(), FieldCount<ContourFittingOptions>());
  EXPECT_EQ(KeyCount<RedundantContourOptions>(), FieldCount<RedundantContourOptions>());
  EXPECT_EQ(KeyCount<PoseGraphOptions>(), FieldCount<PoseGraphOptions>());
  // LoopClosureOptions: its own fields and `graph`.
  EXPECT_EQ(KeyCount<LoopClosureOptions>(), FieldCount<LoopClosureOptions>() - 1 + KeyCount<PoseGraphOptions>());
  // ConcurrentRefinementOptions: loop_closure, pose, fitting and redundant nest; should_stop
  // is a function a caller supplies, not data.
  EXPECT_EQ(KeyCount<ConcurrentRefinementOptions>(),
            FieldCount<ConcurrentRefinementOptions>() - 5 + KeyCount<LoopClosureOptions>() +
                KeyCount<PoseEstimationOptions>() + KeyCount<ContourFittingOptions>() +
                KeyCount<RedundantContourOptions>());
  // ContourMapperOptions: preprocessing, pose, expansion, disappearance, fitting, refinement.
  EXPECT_EQ(KeyCount<ContourMapperOptions>(),
            FieldCount<ContourMapperOptions>() - 6 + KeyCount<ScanPreprocessingOptions>() +
                KeyCount<PoseEstimationOptions>() + KeyCount<MapExpansionOptions>() +
                KeyCount<MapDisappearanceOptions>() + KeyCount<ContourFittingOptions>() +
                KeyCount<ConcurrentRefinementOptions>());
  EXPECT_EQ(KeyCount<MappingSessionOptions>(),
            FieldCount<MappingSessionOptions>() - 1 + KeyCount<ContourMapperOptions>());
  EXPECT_EQ(KeyCount<MapperRunOptions>(), FieldCount<MapperRunOptions>() - 1 + KeyCount<MappingSessionOptions>());
  // The numbers as of this commit, so a reader sees the size of the schema (and a field
  // removed without its declaration shows too).
  EXPECT_EQ(FieldCount<ScanPreprocessingOptions>(), 9u);
  EXPECT_EQ(FieldCount<PoseEstimationOptions>(), 12u);
  EXPECT_EQ(FieldCount<LoopClosureOptions>(), 24u);
  EXPECT_EQ(FieldCount<ConcurrentRefinementOptions>(), 9u);
  EXPECT_EQ(FieldCount<ContourMapperOptions>(), 16u);
  EXPECT_EQ(KeyCount<MapperRunOptions>(), 117u);
}

// A value that `key` accepts and that differs from `value` (its printed default).
std::vector<std::string> OtherValues(const std::string& value) {
  if (value == "true") return {"false"};
  if (value == "false") return {"true"};
  std::vector<std::string> out;
  const double v = std::stod(value);
  const bool integer = value.find_first_of(".e") == std::string::npos;
  for (double d : {v + 1, v - 1, v * 1.5, v * 0.5, v + 0.01, v - 0.01, 0.5, 1.0, 2.0}) {
    std::ostringstream os;
    os.precision(17);
    os << (integer ? static_cast<double>(static_cast<long long>(d)) : d);
    out.push_back(os.str());
  }
  return out;
}

// For every key: setting it through a config text changes the struct in that key's field and
// nowhere else (the printed configuration of the struct differs in exactly that line), so
// every field is reachable by its own name and no two keys share a field.
TEST(MapperOptionsTest, EveryKeyChangesItsOwnFieldAndNoOther) {
  const auto defaults = DeclaredKeys<MapperRunOptions>();
  ASSERT_FALSE(defaults.empty());
  for (size_t k = 0; k < defaults.size(); ++k) {
    const auto& [key, value] = defaults[k];
    bool changed = false;
    for (const std::string& other : OtherValues(value)) {
      MapperRunOptions o;
      ConfigSchema schema("test", "");
      DeclareOptions(OptionScope(schema), o);
      try {
        schema.LoadText(key + " = " + other + "\n", "test");
      } catch (const UsageError&) {
        continue;  // outside the key's range: try another
      }
      // Read back from the struct itself through a second schema over it.
      ConfigSchema reread("test", "");
      DeclareOptions(OptionScope(reread), o);
      std::istringstream text(reread.ConfigText());
      std::vector<std::string> differing;
      size_t i = 0;
      for (std::string line; std::getline(text, line);) {
        if (line.empty() || line[0] == '#') continue;
        if (line != defaults[i].first + " = " + defaults[i].second) differing.push_back(defaults[i].first);
        ++i;
      }
      if (differing.empty()) continue;  // printed the same (rounded): try another
      EXPECT_EQ(differing, std::vector<std::string>{key}) << "setting " << key << " = " << other;
      changed = true;
      break;
    }
    EXPECT_TRUE(changed) << key << " = " << value << ": no other value reached the struct";
  }
}

TEST(MapperOptionsTest, NestedKeysFollowTheStructs) {
  std::map<std::string, std::string> keys;
  for (const auto& [key, value] : DeclaredKeys<MapperRunOptions>()) keys[key] = value;
  EXPECT_EQ(keys.at("mapper.pose.final_threshold"), "0.1");
  EXPECT_EQ(keys.at("mapper.preprocessing.discontinuity_angle"), "0");
  EXPECT_EQ(keys.at("mapper.refinement.pose.initial_threshold"), "0.5");  // DefaultRefinementPoseOptions
  EXPECT_EQ(keys.at("mapper.refinement.loop_closure.graph.huber_scale"), "3");
  EXPECT_EQ(keys.at("mapper.refinement.max_rounds"), "10");  // a run's, not the library's 20
  EXPECT_EQ(keys.at("insert_min_translation"), "0");
  EXPECT_EQ(keys.at("final_refinement_rounds"), "10");
  EXPECT_EQ(keys.at("max_odometry_gap"), "1");
}

// The values of carmen_session_options.h, which mapper/presets/carmen.conf replaced: the
// file must give the same doubles, bit for bit (the CARMEN figures must not move).
TEST(MapperOptionsTest, TheCarmenPresetGivesTheValuesOfTheCPresetItReplacedBitForBit) {
  MapperRunOptions expected;
  MappingSessionOptions& o = expected.session;
  ScanPreprocessingOptions& pre = o.mapper.preprocessing;
  pre.max_range = 40.0;
  pre.discontinuity_threshold = 0.5;
  pre.discontinuity_angle = 0.1745329251994330;  // 10°
  pre.min_points_per_partial_scan = 4;
  o.mapper.pose.initial_threshold = 0.5;
  o.mapper.pose.final_threshold = 0.05;
  o.mapper.pose.heading_search_range = 0.3490658503988659;  // 20°
  o.mapper.pose.heading_search_step = 0.0349065850398866;   // 2°
  o.mapper.pose.heading_search_margin = 0.05;
  o.mapper.min_scan_points = 30;
  o.mapper.max_correction_translation = 1.0;
  o.mapper.max_correction_rotation = 0.35;
  o.insert_min_translation = 0.3;
  o.insert_min_rotation = 0.2;
  o.refine_every_inserts = 0;
  expected.final_refinement_rounds = 0;
  expected.max_odometry_gap = 5.0;

  const MapperRunOptions carmen = MapperPresetOptions("carmen");
  auto bits = [](double v) {
    uint64_t b = 0;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  // Each value the preset sets, bit for bit.
  const MappingSessionOptions& c = carmen.session;
  const std::pair<double, double> set[] = {
      {c.mapper.preprocessing.max_range, pre.max_range},
      {c.mapper.preprocessing.discontinuity_threshold, pre.discontinuity_threshold},
      {c.mapper.preprocessing.discontinuity_angle, pre.discontinuity_angle},
      {c.mapper.pose.initial_threshold, o.mapper.pose.initial_threshold},
      {c.mapper.pose.final_threshold, o.mapper.pose.final_threshold},
      {c.mapper.pose.heading_search_range, o.mapper.pose.heading_search_range},
      {c.mapper.pose.heading_search_step, o.mapper.pose.heading_search_step},
      {c.mapper.pose.heading_search_margin, o.mapper.pose.heading_search_margin},
      {c.mapper.max_correction_translation, o.mapper.max_correction_translation},
      {c.mapper.max_correction_rotation, o.mapper.max_correction_rotation},
      {c.insert_min_translation, o.insert_min_translation},
      {c.insert_min_rotation, o.insert_min_rotation},
      {carmen.max_odometry_gap, expected.max_odometry_gap}};
  for (size_t k = 0; k < std::size(set); ++k) EXPECT_EQ(bits(set[k].first), bits(set[k].second)) << k;
  EXPECT_EQ(c.mapper.preprocessing.min_points_per_partial_scan, 4);
  EXPECT_EQ(c.mapper.min_scan_points, 30);
  EXPECT_EQ(c.refine_every_inserts, 0);
  EXPECT_EQ(carmen.final_refinement_rounds, 0);
  // Nothing else differs from the defaults (the rest of the configuration as printed).
  auto text = [](MapperRunOptions run) {
    ConfigSchema schema("test", "");
    DeclareOptions(OptionScope(schema), run);
    return schema.ConfigText();
  };
  EXPECT_EQ(text(carmen), text(expected));
}

TEST(MapperOptionsTest, TheSurveyPresetIsTheDefaults) {
  auto text = [](MapperRunOptions run) {
    ConfigSchema schema("test", "");
    DeclareOptions(OptionScope(schema), run);
    return schema.ConfigText();
  };
  EXPECT_EQ(text(MapperPresetOptions("survey")), text(MapperRunOptions{}));
  EXPECT_EQ(MapperPresetNames(), (std::vector<std::string>{"survey", "carmen"}));
}

// defaults < preset < config file < flags, and errors name the preset's line.
TEST(MapperOptionsTest, APresetIsALayerUnderTheConfigFileAndTheFlags) {
  MapperRunOptions o;
  ConfigSchema schema("test", "");
  DeclareOptions(OptionScope(schema), o);
  LoadMapperPreset(schema, "carmen");
  EXPECT_EQ(o.session.mapper.pose.final_threshold, 0.05);
  EXPECT_EQ(o.session.mapper.min_scan_points, 30);
  schema.LoadText("mapper.pose.final_threshold = 0.07\n", "a.conf");
  ASSERT_EQ(schema.Parse(std::vector<std::string>{"--mapper.min-scan-points", "40"}), ParseOutcome::kRun);
  EXPECT_EQ(o.session.mapper.pose.final_threshold, 0.07);
  EXPECT_EQ(o.session.mapper.min_scan_points, 40);
  EXPECT_EQ(o.session.mapper.preprocessing.max_range, 40.0);  // the preset's, untouched
  EXPECT_EQ(o.max_odometry_gap, 5.0);

  try {
    MapperPresetText("mine");
    FAIL() << "no such preset";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("survey, carmen"), std::string::npos) << e.what();
  }
  ConfigSchema missing("test", "");  // a schema without the run's keys
  try {
    LoadMapperPreset(missing, "carmen");
    FAIL() << "unknown keys";
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("preset carmen:", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace minenav::mapper
