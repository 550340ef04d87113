#pragma once
// The live contour mapper as the pose source of a simulation: what the live fleet runs
// (ladar_driver -> contour_mapper -> POSE and CONTOUR_MAP), in-process, for the tracker's
// and the cutter's closed loops in simulation and bench/tracker_bench.cc (this library links
// sim/ and sensor_driver/: tests and benches only, never the tracker's own targets).
//
//   * the scan: sensor_driver's LadarSimulator (ladar_driver's) ray-casts the TRUE world from
//     the TRUE pose (the Typhoon by default: 2048 points, 4.4 cm noise and quantisation, mixed
//     pixels);
//   * the estimate: the contour mapper's MappingSession (mapper/mapping_session.h, the
//     contour_mapper process's policy) takes the scan with the odometry pose at its time; it
//     INSERTS it when the vehicle moved insert_min_translation or turned insert_min_rotation
//     since the last insert (the demo's 1 m / 0.3 rad) and TRACKS it otherwise; the first
//     scan anchors the map at its odometry pose (give the odometry in the world frame, as
//     vehicle_sim does, and the map's frame is the world's). The estimate is what the node
//     publishes on POSE (MakePoseEstimate: zero covariance, unconverged when refused); a new
//     map (after an insert) is what it publishes on CONTOUR_MAP;
//   * its latency: the mapper is one worker taking the scans in order, each after the
//     previous one is done, and a scan's computation takes the thread CPU time the session
//     really spent on it (or, for a test that must not depend on the machine, a fixed
//     `compute_time`), plus transport_latency. So the estimate of a scan taken at t is out at
//     max(t, worker free) + compute + transport.

#include <cstdint>
#include <limits>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/pose_estimate.h"
#include "common/segment_index.h"
#include "mapper/contour_map.h"
#include "mapper/mapping_session.h"
#include "sensor_driver/ladar_model.h"
#include "sensor_driver/ladar_simulator.h"

namespace minenav::testing {

// The live fleet's mapping policy (fleet/mission.fleet): insert a scan every metre or
// 0.3 rad, track the others; an insert refits with the 20 nearest scans within 15 m.
mapper::MappingSessionOptions LiveMappingPolicy();

struct MapperPoseSourceOptions {
  LadarModel ladar = LadarModel::Typhoon();
  uint64_t seed = 1;                   // of the ladar's noise
  mapper::MappingSessionOptions session = LiveMappingPolicy();
  double compute_time = -1.0;          // s per scan; < 0: the thread CPU time the session took (measured)
  double transport_latency = 0.01;     // s, from the mapper's answer to the consumer
};

// The segments of a contour map (what a consumer of CONTOUR_MAP checks against).
std::vector<Segment> MapSegments(const mapper::ContourMap& map);

class MapperPoseSource {
 public:
  explicit MapperPoseSource(MapperPoseSourceOptions options = {});

  struct Output {
    PoseEstimate estimate;          // as published on POSE
    mapper::ScanOutcome outcome = mapper::ScanOutcome::kRefused;
    bool map_changed = false;       // inserted: a new CONTOUR_MAP goes out with the estimate
    double compute_seconds = 0.0;   // the computation's time (measured, or the fixed compute_time)
    double ready_at = 0.0;          // s (the caller's clock) when the estimate is out
  };
  // A scan taken at `now_s` (s, the caller's clock; stamped `utime`) of `world` with the
  // vehicle truly at `truth` and its odometry reading `odometry`.
  Output Scan(const StaticSegmentIndex& world, const Pose2& truth, const Pose2& odometry, int64_t utime,
              double now_s);
  // The same for a world that changes between scans (the index is built for this scan).
  Output Scan(const std::vector<Segment>& world, const Pose2& truth, const Pose2& odometry, int64_t utime,
              double now_s);

  const mapper::MappingSession& session() const { return session_; }
  const mapper::ContourMap& map() const { return session_.map(); }
  std::vector<Segment> MapSegments() const { return testing::MapSegments(session_.map()); }
  const MapperPoseSourceOptions& options() const { return options_; }

 private:
  MapperPoseSourceOptions options_;
  LadarSimulator ladar_;
  mapper::MappingSession session_;
  double worker_free_at_ = -std::numeric_limits<double>::infinity();
  int64_t scan_id_ = 0;
};

}  // namespace minenav::testing
