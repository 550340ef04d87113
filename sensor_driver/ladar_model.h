#pragma once
// Parameters of a simulated planar 360 deg ladar.
//
// Thesis 5.2.1 lists what controlled synthetic scan generation: number of scan points,
// maximum range, minimum range, start angle, angular resolution, range resolution, standard
// deviation of range. We add what the real sensors of Appendices B and C show and 2.2
// describes: beam divergence, mixed pixels at occlusions ("the laser beam reflected
// partially from the near object and partially from the further object. Typically, this
// resulted in a reported range somewhere between the two objects"), scan rate, sensor id.
//
// Mixed pixels: the beam's footprint spans beam_divergence around each reading's bearing.
// If the two edges of the footprint see surfaces whose ranges differ by more than
// mixed_pixel_min_gap (an occlusion edge inside the footprint), then with probability
// mixed_pixel_probability the reading is replaced by a range drawn uniformly between the
// near and the far surface (then noise and quantisation apply as usual).

#include <string>

namespace minenav {

struct LadarModel {
  std::string sensor_id = "typhoon";
  int num_points = 2048;            // readings per revolution
  double min_range = 1.5;           // m; shorter measurements are reported as no return
  double max_range = 45.0;          // m; longer measurements are reported as no return
  double start_angle = 0.0;         // rad, bearing of reading 0 in the sensor frame
  double angular_resolution = 0.0;  // rad between readings (signed); 0 = 2 pi / num_points
  double range_resolution = 0.044;  // m, ranges are rounded to multiples of this; 0 = none
  double range_sigma = 0.044;       // m, std of Gaussian range noise
  double beam_divergence = 0.003;   // rad, full horizontal divergence of the beam
  double beam_divergence_vertical = 0.001;  // rad, recorded for completeness (2D: unused)
  double mixed_pixel_probability = 0.5;     // chance a footprint straddling an edge mixes
  double mixed_pixel_min_gap = 0.3;         // m, range jump inside a footprint that counts as an edge
  double scan_rate = 10.0;          // Hz, revolutions per second (scan_duration = 1 / rate)

  // Resolved angular step: angular_resolution, or 2 pi / num_points when it is 0.
  double AngleStep() const;
  // "" when usable, else a one-line reason naming the parameter.
  std::string Validate() const;

  // K2T Typhoon, Appendix C: 2048 points, 1.5-45 m, range resolution and 1 std ~4.4 cm,
  // divergence 1 x 3 mrad (we take the wider 3 mrad as horizontal, the worse case for
  // mixed pixels), ~10 Hz (20 kHz pulse rate / 2048 points = 9.8 Hz).
  static LadarModel Typhoon();
  // CMU Cyclone, Appendix B: 512-8192 points per revolution, useful 4-50 m, resolution
  // 10 cm, 1 std ~10 cm, divergence 4 mrad. Scan rate: the rotation (up to 7 Hz; 5 Hz used)
  // limited by the 7.2 kHz pulse rate, i.e. min(5, 7200 / points) Hz.
  static LadarModel Cyclone(int points = 2048);
  // No noise, no quantisation, no mixed pixels, no divergence: exact ray casting.
  LadarModel Ideal() const;
};

}  // namespace minenav
