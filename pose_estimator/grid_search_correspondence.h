#pragma once
// Grid-search correspondence, a simplified Gonzalez (1992) as the thesis compared it
// (3.1.1, 3.7): each grid cell lists the segments drawn through it; a query visits every
// cell within the correspondence threshold of the point and measures every segment listed
// there. O(N) in the scan for a bounded threshold, but many cells per point.
//
// Not safe for concurrent Nearest() calls on one object (it keeps a visit stamp per segment).

#include <cstdint>
#include <vector>

#include "pose_estimator/correspondence.h"
#include "pose_estimator/segment_grid.h"

namespace minenav {

class GridSearchCorrespondence : public CorrespondenceSearch {
 public:
  // cell_size in m.
  GridSearchCorrespondence(std::vector<Segment> segments, double cell_size);
  SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const override;
  const std::vector<Segment>& segments() const override { return segments_; }
  const char* name() const override { return "grid"; }

 private:
  std::vector<Segment> segments_;
  std::vector<PreparedSegment> prepared_;
  GridFrame frame_;
  std::vector<int32_t> offsets_;  // CSR: cell k lists ids_[offsets_[k] .. offsets_[k+1])
  std::vector<int32_t> ids_;
  mutable std::vector<uint32_t> stamp_;  // last query that measured each segment
  mutable uint32_t query_ = 0;
};

}  // namespace minenav
