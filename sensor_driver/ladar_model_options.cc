#include "sensor_driver/ladar_model_options.h"

#include "common/config.h"

namespace minenav {
namespace {

constexpr const char* kPresetsOwn = "; empty = the sensor's";

// One override: "" keeps *value; else the number. `name` is the key under the scope.
void Override(const std::string& text, const std::string& scope_prefix, const std::string& name, bool angle,
              double* value) {
  if (text.empty()) return;
  std::string flag = "--" + name;
  for (char& c : flag)
    if (c == '_') c = '-';
  const std::string what = scope_prefix.empty() ? flag : scope_prefix + name + " (" + flag + ")";
  *value = ParseNumber(text, what, angle);
}

}  // namespace

void DeclareOptions(OptionScope scope, LadarModelOptions& o) {
  scope.AddString("sensor", &o.sensor, "sensor model: K2T Typhoon (App. C) or CMU Cyclone (App. B)",
                  {"typhoon", "cyclone"});
  scope.AddInt("points", &o.points, "readings per revolution; 0 = the sensor's (typhoon 2048, cyclone 2048)", 0,
               1 << 20);
  const std::string own = kPresetsOwn;
  scope.AddString("sensor_id", &o.sensor_id, "sensor_id in the scans" + own + " name");
  scope.AddString("min_range", &o.min_range,
                  "[m] shorter returns are no return" + own + " (typhoon 1.5, cyclone 4)");
  scope.AddString("max_range", &o.max_range,
                  "[m] longer returns are no return" + own + " (typhoon 45, cyclone 50)");
  scope.AddString("start_angle", &o.start_angle, "[rad, or e.g. -180deg] bearing of reading 0" + own + " (0)");
  scope.AddString("angular_resolution", &o.angular_resolution,
                  "[rad, or deg] signed step between readings; 0 = 2 pi / points" + own);
  scope.AddString("range_resolution", &o.range_resolution,
                  "[m] ranges are rounded to this; 0 = none" + own + " (typhoon 0.044, cyclone 0.1)");
  scope.AddString("range_sigma", &o.range_sigma,
                  "[m] std of Gaussian range noise" + own + " (typhoon 0.044, cyclone 0.1)");
  scope.AddString("beam_divergence", &o.beam_divergence,
                  "[rad] full horizontal beam divergence" + own + " (typhoon 0.003, cyclone 0.004)");
  scope.AddString("beam_divergence_vertical", &o.beam_divergence_vertical,
                  "[rad] full vertical beam divergence, recorded only (the world is 2D)" + own +
                      " (typhoon 0.001, cyclone 0.004)");
  scope.AddString("mixed_pixel_probability", &o.mixed_pixel_probability,
                  "[0..1] chance a footprint straddling an occlusion edge reports a range in between" + own +
                      " (typhoon 0.5, cyclone 0.8)");
  scope.AddString("mixed_pixel_min_gap", &o.mixed_pixel_min_gap,
                  "[m] range jump inside a footprint that counts as an edge" + own + " (0.3)");
  scope.AddString("scan_rate", &o.scan_rate,
                  "[Hz] revolutions per second" + own + " (typhoon 10, cyclone min(5, 7200 / points))");
}

LadarModel BuildLadarModel(const LadarModelOptions& o, const std::string& scope_prefix) {
  LadarModel m = o.sensor == "cyclone" ? LadarModel::Cyclone(o.points > 0 ? o.points : 2048) : LadarModel::Typhoon();
  if (o.points > 0 && o.points != m.num_points) {
    m.num_points = o.points;
    m.angular_resolution = 0.0;  // 2 pi / points unless given below
  }
  if (!o.sensor_id.empty()) m.sensor_id = o.sensor_id;
  const std::string& p = scope_prefix;
  Override(o.min_range, p, "min_range", false, &m.min_range);
  Override(o.max_range, p, "max_range", false, &m.max_range);
  Override(o.start_angle, p, "start_angle", true, &m.start_angle);
  Override(o.angular_resolution, p, "angular_resolution", true, &m.angular_resolution);
  Override(o.range_resolution, p, "range_resolution", false, &m.range_resolution);
  Override(o.range_sigma, p, "range_sigma", false, &m.range_sigma);
  Override(o.beam_divergence, p, "beam_divergence", true, &m.beam_divergence);
  Override(o.beam_divergence_vertical, p, "beam_divergence_vertical", true, &m.beam_divergence_vertical);
  Override(o.mixed_pixel_probability, p, "mixed_pixel_probability", false, &m.mixed_pixel_probability);
  Override(o.mixed_pixel_min_gap, p, "mixed_pixel_min_gap", false, &m.mixed_pixel_min_gap);
  Override(o.scan_rate, p, "scan_rate", false, &m.scan_rate);
  if (const std::string why = m.Validate(); !why.empty()) throw UsageError("sensor model: " + why);
  return m;
}

}  // namespace minenav
