#include "sensor_driver/ladar_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/angle.h"

namespace minenav {

double LadarModel::AngleStep() const {
  if (angular_resolution != 0.0) return angular_resolution;
  return num_points > 0 ? 2.0 * kPi / num_points : 0.0;
}

std::string LadarModel::Validate() const {
  std::ostringstream why;
  auto finite = [](double v) { return std::isfinite(v); };
  if (sensor_id.empty())
    why << "sensor_id must not be empty";
  else if (num_points < 1 || num_points > 1000000)
    why << "num_points must be in [1, 1000000] (got " << num_points << ")";
  else if (!finite(min_range) || min_range < 0.0)
    why << "min_range must be >= 0 m (got " << min_range << ")";
  else if (!finite(max_range) || !(max_range > min_range))
    why << "max_range must be finite and > min_range (got " << max_range << " <= " << min_range << ")";
  else if (!finite(start_angle))
    why << "start_angle must be finite (got " << start_angle << ")";
  else if (!finite(angular_resolution) || std::abs(AngleStep()) * num_points > 2.0 * kPi + 1e-9)
    why << "angular_resolution * num_points exceeds 360 deg (" << angular_resolution << " rad x " << num_points << ")";
  else if (!finite(range_resolution) || range_resolution < 0.0)
    why << "range_resolution must be >= 0 m (got " << range_resolution << ")";
  else if (!finite(range_sigma) || range_sigma < 0.0)
    why << "range_sigma must be >= 0 m (got " << range_sigma << ")";
  else if (!finite(beam_divergence) || beam_divergence < 0.0 || beam_divergence > 0.1)
    why << "beam_divergence must be in [0, 0.1] rad (got " << beam_divergence << ")";
  else if (!finite(beam_divergence_vertical) || beam_divergence_vertical < 0.0 || beam_divergence_vertical > 0.1)
    why << "beam_divergence_vertical must be in [0, 0.1] rad (got " << beam_divergence_vertical << ")";
  else if (!finite(mixed_pixel_probability) || mixed_pixel_probability < 0.0 || mixed_pixel_probability > 1.0)
    why << "mixed_pixel_probability must be in [0, 1] (got " << mixed_pixel_probability << ")";
  else if (!finite(mixed_pixel_min_gap) || mixed_pixel_min_gap < 0.0)
    why << "mixed_pixel_min_gap must be >= 0 m (got " << mixed_pixel_min_gap << ")";
  else if (!finite(scan_rate) || !(scan_rate > 0.0))
    why << "scan_rate must be > 0 Hz (got " << scan_rate << ")";
  return why.str();
}

LadarModel LadarModel::Typhoon() {
  LadarModel m;
  m.sensor_id = "typhoon";
  m.num_points = 2048;
  m.min_range = 1.5;
  m.max_range = 45.0;
  m.start_angle = 0.0;
  m.angular_resolution = 2.0 * kPi / 2048;
  m.range_resolution = 0.044;
  m.range_sigma = 0.044;
  m.beam_divergence = 0.003;
  m.beam_divergence_vertical = 0.001;
  m.mixed_pixel_probability = 0.5;
  m.mixed_pixel_min_gap = 0.3;
  m.scan_rate = 10.0;
  return m;
}

LadarModel LadarModel::Cyclone(int points) {
  LadarModel m;
  m.sensor_id = "cyclone";
  m.num_points = points;
  m.min_range = 4.0;
  m.max_range = 50.0;
  m.start_angle = 0.0;
  m.angular_resolution = points > 0 ? 2.0 * kPi / points : 0.0;
  m.range_resolution = 0.10;
  m.range_sigma = 0.10;
  m.beam_divergence = 0.004;
  m.beam_divergence_vertical = 0.004;
  // 2.2: "Outliers occurred mostly at occlusions"; Cyclone "seems to be more susceptible
  // to outliers caused by mixed points" (4.2) than Typhoon.
  m.mixed_pixel_probability = 0.8;
  m.mixed_pixel_min_gap = 0.3;
  m.scan_rate = points > 0 ? std::min(5.0, 7200.0 / points) : 5.0;
  return m;
}

LadarModel LadarModel::Ideal() const {
  LadarModel m = *this;
  m.range_resolution = 0.0;
  m.range_sigma = 0.0;
  m.beam_divergence = 0.0;
  m.mixed_pixel_probability = 0.0;
  return m;
}

}  // namespace minenav
