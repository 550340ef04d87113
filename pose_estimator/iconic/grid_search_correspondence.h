#pragma once
// Grid-search correspondence, a simplified Gonzalez (1992) as the thesis compared it
// (3.1.1, 3.7): each grid cell lists the segments drawn through it; a query visits every
// cell within the correspondence threshold of the point and measures every segment listed
// there. O(N) in the scan for a bounded threshold, but many cells per point. The grid is the
// fleet's StaticSegmentIndex (common/segment_index.h).
//
// Not safe for concurrent Nearest() calls on one object (it keeps a visit stamp per segment).

#include <cstdint>
#include <vector>

#include "common/segment_index.h"
#include "pose_estimator/iconic/correspondence.h"

namespace minenav {

class GridSearchCorrespondence : public CorrespondenceSearch {
 public:
  // cell_size in m.
  GridSearchCorrespondence(std::vector<Segment> segments, double cell_size);
  SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const override;
  const std::vector<Segment>& segments() const override { return index_.segments(); }
  const char* name() const override { return "grid"; }

 private:
  StaticSegmentIndex index_;
  std::vector<PreparedSegment> prepared_;
  mutable std::vector<uint32_t> stamp_;  // last query that measured each segment
  mutable uint32_t query_ = 0;
};

}  // namespace minenav
