#pragma once
// Brute-force correspondence (Cox 1991, thesis 3.1.1 and 3.7): the distance from every
// point to every segment, O(MN). The reference the faster searches are tested against.

#include "pose_estimator/iconic/correspondence.h"

namespace minenav {

class BruteForceCorrespondence : public CorrespondenceSearch {
 public:
  explicit BruteForceCorrespondence(std::vector<Segment> segments)
      : segments_(std::move(segments)), prepared_(PrepareSegments(segments_)) {}
  SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const override;
  const std::vector<Segment>& segments() const override { return segments_; }
  const char* name() const override { return "brute"; }

 private:
  std::vector<Segment> segments_;
  std::vector<PreparedSegment> prepared_;
};

}  // namespace minenav
