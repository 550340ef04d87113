#pragma once
// The sensor model a program runs with, as options: a preset (LadarModel::Typhoon() or
// Cyclone(points)) and an override for every parameter of LadarModel. The overrides are
// text so that "" means "the preset's own value"; numbers follow common/config.h (angles
// also as e.g. 0.2deg).

#include <string>

#include "sensor_driver/ladar_model.h"

namespace minenav {

struct LadarModelOptions {
  std::string sensor = "typhoon";  // typhoon | cyclone
  int points = 0;                  // readings per revolution; 0 = the preset's
  std::string sensor_id, min_range, max_range, start_angle, angular_resolution, range_resolution, range_sigma,
      beam_divergence, beam_divergence_vertical, mixed_pixel_probability, mixed_pixel_min_gap, scan_rate;
};

class OptionScope;
// Declares every field of LadarModelOptions under `scope` (unit, meaning, the presets' values).
void DeclareOptions(OptionScope scope, LadarModelOptions& o);

// The preset with the overrides applied. Throws UsageError naming the option (in the
// words of `scope_prefix`, e.g. "model.", and its flat flag) when an override is not a
// number, or "sensor model: ..." when LadarModel::Validate refuses the result.
LadarModel BuildLadarModel(const LadarModelOptions& o, const std::string& scope_prefix = "");

}  // namespace minenav
