#pragma once
// A map made of several scans, each kept in its own frame with its own lookup table
// (thesis 3.4, "one to many"): a point is matched to every scan near it and the nearest
// segment over all of them wins. Tables are built once per scan and never rebuilt when
// scans are added, so matching the k-th scan to the k-1 before it stays cheap.
//
// segments() are the scans' segments in the map frame, indexed by offset(scan) + index.

#include <memory>
#include <vector>

#include "common/pose2.h"
#include "pose_estimator/iconic/correspondence.h"
#include "pose_estimator/iconic/lookup_table_correspondence.h"

namespace minenav {

class ScanSetMap : public CorrespondenceSearch {
 public:
  // cell_size (m, 0 = automatic) and reach (m) for each scan's lookup table.
  ScanSetMap(double cell_size, double reach) : cell_size_(cell_size), reach_(reach) {}

  // Adds a scan's segments (in the scan's own frame) placed at `pose` in the map frame.
  // Returns the scan's index.
  int AddScan(std::vector<Segment> segments_in_scan_frame, const Pose2& pose);
  int num_scans() const { return static_cast<int>(members_.size()); }
  // The scan and the index in its own segment list of a global segment index.
  std::pair<int, int> Locate(int global_segment) const;
  const Pose2& pose(int scan) const { return members_[static_cast<size_t>(scan)].pose; }
  const std::vector<Segment>& local_segments(int scan) const {
    return members_[static_cast<size_t>(scan)].table->segments();
  }

  SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const override;
  const std::vector<Segment>& segments() const override { return world_segments_; }
  const char* name() const override { return "scan-set"; }

 private:
  struct Member {
    Pose2 pose;
    Pose2 inverse;
    Eigen::Vector2d centre;  // bounding circle of the segments, map frame
    double radius = 0.0;
    int offset = 0;
    std::unique_ptr<LookupTableCorrespondence> table;
  };
  double cell_size_, reach_;
  std::vector<Member> members_;
  std::vector<Segment> world_segments_;
};

// Bounding circle (centre, radius) of segments.
std::pair<Eigen::Vector2d, double> BoundingCircle(const std::vector<Segment>& segments);

}  // namespace minenav
