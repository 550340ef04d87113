#pragma once
// The thesis's lookup-table correspondence (3.1.1): the map is drawn into a grid, and the
// marked cells are grown with a grassfire transform [Duda73] out to `reach`, so that every
// cell within reach of the map holds the short list of segments that can be nearest to
// some point of that cell. A query visits exactly one cell and measures only its list.
//
// Unlike the thesis's single "pointer to the nearest marked cell", the lists here are
// exact: a segment is kept in a cell unless some other segment is certainly nearer to
// every point of the cell (least box distance of one > greatest box distance of the
// other). Growth repeats until no list changes. Because every point on the line from a
// query to its nearest point is also nearest to that segment, the segment reaches the
// query's cell along that line, so results equal brute force for any threshold <= reach.

#include <cstdint>
#include <vector>

#include "common/segment_index.h"
#include "pose_estimator/iconic/correspondence.h"

namespace minenav {

class LookupTableCorrespondence : public CorrespondenceSearch {
 public:
  // cell_size and reach in m.
  LookupTableCorrespondence(std::vector<Segment> segments, double cell_size, double reach);
  SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const override;
  const std::vector<Segment>& segments() const override { return segments_; }
  const char* name() const override { return "lookup"; }

  double reach() const { return reach_; }
  const GridFrame& frame() const { return frame_; }
  // Statistics of the list lengths over the grown cells (for the README's figures).
  double MeanListLength() const;
  int MaxListLength() const;
  int64_t GrownCells() const;

 private:
  std::vector<Segment> segments_;
  std::vector<PreparedSegment> prepared_;
  double reach_ = 0.0;
  GridFrame frame_;
  double inv_cell_ = 1.0;
  std::vector<int32_t> offsets_;  // CSR over cells
  std::vector<int32_t> ids_;
};

}  // namespace minenav
