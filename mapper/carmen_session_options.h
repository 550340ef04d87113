#pragma once
// One set of mapping-session options for the public CARMEN logs (Intel, Freiburg 079, MIT
// CSAIL, Freiburg hospital; shared/datasets/SOURCES.md): a SICK LMS with 180° at 1° or
// 0.5°, ranges to ~80 m, on a robot that scans at 5–10 Hz while it drives at ~0.5 m/s, with
// people walking past. The same values serve every log (issue #7: no special case for one
// dataset); bench/mapper_carmen_bench.cc and mapper/carmen_regression_test.cc both use them,
// so the CI slice checks what the table reports.
//
// Why each value differs from the synthetic-mine defaults (360° Typhoon scans at survey
// stations, thesis 5.2):
//   * max_range 40 m: beyond it 1° readings are > 0.7 m apart and the SICK's no-return
//     codes (81.83 / 81.91 m) are already removed by the reader; far points add leverage
//     for heading but also most of the mixed readings through doors and windows.
//   * discontinuity_angle 10°: range-adaptive partial-scan breaks (scan_preprocessing.h);
//     with a fixed 0.5 m, walls beyond ~20 m fall apart into single points.
//   * pose.initial_threshold 0.5 m: every scan starts from the previous estimate moved by
//     the odometry since it (0.05–0.1 s of motion), so the start is within centimetres;
//     3 m (the survey default) would let far clutter pull the estimate.
//   * pose.final_threshold 0.05 m: the SICK's range noise is ~1 cm (the Typhoon's 4.4 cm
//     needs 0.1 m); on the first 1500 Intel scans 0.1 m gives 0.0195 m / 0.244° and 0.05 m
//     0.0170 m / 0.231° (relations inside the slice).
//   * pose.heading_search_range 20°: MIT CSAIL's odometry (the FLASER lines' triple) lags
//     turns, e.g. 0° for four scans then 50° in one, and the line searches from such a start
//     lock onto the wrong walls; a second descent from the best-matching heading, kept only
//     when its final fit is better (pose_estimation.h), takes the first 500 CSAIL scans from
//     0.068 m / 2.06° to 0.029 m / 0.70° and leaves Intel unchanged within noise.
//   * insert every 0.3 m or 0.2 rad: scans in between are tracked against the map (their
//     poses are reported and scored) but do not edit it; 10 Hz inserts would make the
//     refit cost grow with the number of near-identical scans over every wall.

#include "mapper/mapping_session.h"

namespace minenav::mapper {

inline MappingSessionOptions CarmenSessionOptions() {
  MappingSessionOptions o;
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
  return o;
}

}  // namespace minenav::mapper
