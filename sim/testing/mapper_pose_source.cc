#include "sim/testing/mapper_pose_source.h"

#include <algorithm>
#include <utility>

#include "common/node/cpu_time.h"

namespace minenav::testing {

mapper::MappingSessionOptions LiveMappingPolicy() {
  mapper::MappingSessionOptions o;
  o.insert_min_translation = 1.0;
  o.insert_min_rotation = 0.3;
  // An insert refits with the 20 scans nearest to it, vertices within 15 m of the sensor
  // (fleet/mission.fleet: a live mapper whose insert cost does not grow with the map).
  o.mapper.fit_scans = 20;
  o.mapper.local_fit_radius = 15.0;
  return o;
}

std::vector<Segment> MapSegments(const mapper::ContourMap& map) {
  std::vector<Segment> out;
  for (const auto& [id, c] : map.contours())
    for (int k = 0; k < c.NumSegments(); ++k) out.push_back(c.GetSegment(k));
  return out;
}

MapperPoseSource::MapperPoseSource(MapperPoseSourceOptions options)
    : options_(std::move(options)), ladar_(options_.ladar, options_.seed), session_(options_.session) {}

MapperPoseSource::Output MapperPoseSource::Scan(const std::vector<Segment>& world, const Pose2& truth,
                                                const Pose2& odometry, int64_t utime, double now_s) {
  return Scan(StaticSegmentIndex(world), truth, odometry, utime, now_s);
}

MapperPoseSource::Output MapperPoseSource::Scan(const StaticSegmentIndex& world, const Pose2& truth,
                                                const Pose2& odometry, int64_t utime, double now_s) {
  const int64_t id = scan_id_++;
  const LadarScan scan = ladar_.Simulate(world, truth, Pose2(), utime, id);
  const double cpu0 = ThreadCpuSeconds();
  const mapper::ScanResult r = session_.AddScan(scan, odometry);
  Output out;
  out.compute_seconds = options_.compute_time >= 0.0 ? options_.compute_time : ThreadCpuSeconds() - cpu0;
  out.estimate = MakePoseEstimate(r, utime, id, "clue", out.compute_seconds);
  out.outcome = r.outcome;
  out.map_changed = r.outcome == mapper::ScanOutcome::kInserted;
  const double start = std::max(now_s, worker_free_at_);
  worker_free_at_ = start + out.compute_seconds;
  out.ready_at = worker_free_at_ + options_.transport_latency;
  return out;
}

}  // namespace minenav::testing
