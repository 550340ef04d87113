#include "sensor_driver/ladar_simulator.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace minenav {

namespace {

uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

}  // namespace

LadarSimulator::LadarSimulator(const LadarModel& model, uint64_t seed) : model_(model), seed_(seed) {
  const std::string why = model_.Validate();
  if (!why.empty()) throw std::invalid_argument("ladar model: " + why);
}

LadarScan LadarSimulator::Simulate(const std::vector<Segment>& world, const Pose2& world_T_vehicle,
                                   const Pose2& sensor_offset, int64_t utime, int64_t scan_id) const {
  return Simulate(StaticSegmentIndex(world), world_T_vehicle, sensor_offset, utime, scan_id);
}

LadarScan LadarSimulator::Simulate(const StaticSegmentIndex& world, const Pose2& world_T_vehicle,
                                   const Pose2& sensor_offset, int64_t utime, int64_t scan_id) const {
  return SimulateDetailed(world, world_T_vehicle, sensor_offset, utime, scan_id).scan;
}

SimulatedScan LadarSimulator::SimulateDetailed(const StaticSegmentIndex& world, const Pose2& world_T_vehicle,
                                               const Pose2& sensor_offset, int64_t utime,
                                               int64_t scan_id) const {
  const LadarModel& m = model_;
  const size_t n = static_cast<size_t>(m.num_points);
  const double step = m.AngleStep();

  SimulatedScan out;
  LadarScan& scan = out.scan;
  scan.utime = utime;
  scan.scan_id = scan_id;
  scan.sensor_id = m.sensor_id;
  scan.sensor_offset = sensor_offset;
  scan.start_angle = m.start_angle;
  scan.angle_step = step;
  scan.min_range = m.min_range;
  scan.max_range = m.max_range;
  scan.range_resolution = m.range_resolution;
  scan.scan_duration = (std::abs(step) * static_cast<double>(n - 1) / (2.0 * kPi)) / m.scan_rate;
  scan.ranges.assign(n, 0.0f);
  out.true_range.assign(n, 0.0);
  out.hit_segment.assign(n, -1);
  out.mixed.assign(n, 0);

  const Pose2 world_T_sensor = world_T_vehicle * sensor_offset;
  const Eigen::Vector2d origin = world_T_sensor.translation();
  // Cast a little past max_range: noise can bring a slightly farther surface into range.
  const double cast_range = m.max_range + 6.0 * m.range_sigma + m.range_resolution;
  const bool mixing = m.mixed_pixel_probability > 0.0 && m.beam_divergence > 0.0;
  const double half_beam = 0.5 * m.beam_divergence;

  std::mt19937_64 rng(SplitMix64(seed_ ^ SplitMix64(static_cast<uint64_t>(scan_id))));
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);

  for (size_t i = 0; i < n; ++i) {
    // Same draws for every reading, hit or not, so readings do not shift each other's noise.
    const double noise = gauss(rng);
    const double u_mix = unit(rng);
    const double u_where = unit(rng);

    const double bearing = world_T_sensor.theta + m.start_angle + static_cast<double>(i) * step;
    const auto hit = world.CastRay(origin, bearing, cast_range);
    if (!hit) continue;
    out.true_range[i] = hit->range;
    out.hit_segment[i] = hit->segment;

    double r = hit->range;
    if (mixing && u_mix < m.mixed_pixel_probability) {
      // The footprint's two edges; an occlusion edge inside it mixes near and far returns.
      const auto left = world.CastRay(origin, bearing + half_beam, cast_range);
      const auto right = world.CastRay(origin, bearing - half_beam, cast_range);
      if (left && right) {
        const double near = std::min({r, left->range, right->range});
        const double far = std::max({r, left->range, right->range});
        if (far - near > m.mixed_pixel_min_gap) {
          r = near + u_where * (far - near);
          out.mixed[i] = 1;
          ++out.num_mixed;
        }
      }
    }
    r += m.range_sigma * noise;
    if (m.range_resolution > 0.0) r = std::round(r / m.range_resolution) * m.range_resolution;
    if (r >= m.min_range && r <= m.max_range) scan.ranges[i] = static_cast<float>(r);
  }
  return out;
}

}  // namespace minenav
