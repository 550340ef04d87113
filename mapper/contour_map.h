#pragma once
// The contour map (thesis 4.1): a set of contours with stable ids, the edit operations that
// map expansion (4.4) and the dynamic-world editing of 4.8.1 need, and a segment index
// (common/segment_index.h, one group per contour, re-indexed as a whole on every edit) that
// every edit keeps in step. All edits go through this class so the index never goes stale.
//
// Edit operations (4.8.1 names):
//   Create   a new contour from points.
//   Cut      insert a vertex inside a segment (two segments where there was one).
//   Detach   split a contour at a vertex, the vertex duplicated (a closed contour opens).
//   Extend   add points beyond the start or the end of an open contour.
//   Join     connect the end of one open contour to the start of another (or its own start,
//            which closes it) through optional bridge points.
//   Splice   cut a segment and connect another contour's start or end to the new vertex;
//            the rest of the cut contour stays a contour of its own (left alone, 4.8).

#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

#include "common/segment_index.h"
#include "mapper/contour.h"

namespace minenav::mapper {

class ContourMap {
 public:
  explicit ContourMap(double grid_cell_size = 2.0) : grid_(grid_cell_size) {}
  ContourMap(const ContourMap& other) = default;
  ContourMap& operator=(const ContourMap& other) = default;

  // --- access
  const Contour* Find(int id) const;
  const Contour& Get(int id) const;  // id must exist
  std::vector<int> Ids() const;
  int NumContours() const { return static_cast<int>(contours_.size()); }
  int NumSegments() const;
  double TotalLength() const;
  const std::map<int, Contour>& contours() const { return contours_; }
  // The index: group = contour id, index = segment of the contour.
  const IncrementalSegmentIndex& grid() const { return grid_; }
  // Candidate segments within `radius` of p (superset; callers test exact distance), sorted.
  std::vector<SegmentRef> SegmentsNear(const Eigen::Vector2d& p, double radius) const;
  // Calls fn(SegmentRef) for candidates within `radius` of p without allocating (may repeat
  // a segment; callers test exact distance).
  template <typename Fn>
  void ForEachSegmentNear(const Eigen::Vector2d& p, double radius, Fn&& fn) const {
    grid_.ForEachNear(p, radius, [&](const SegmentId& id) { fn(SegmentRef{id.group, id.index}); });
  }

  // --- edits. Each returns the id(s) it produced; ids of removed contours are never reused.
  // Creates a contour (needs >= 2 points, >= 3 when closed).
  int Create(std::vector<Eigen::Vector2d> points, bool closed = false);
  // Replaces a contour's vertices (fitting, resampling). Open needs >= 2, closed >= 3.
  void SetPoints(int id, std::vector<Eigen::Vector2d> points);
  void Remove(int id);
  void Clear();

  // Inserts `point` as a new vertex inside segment k; returns the new vertex's index.
  int Cut(int id, int segment, const Eigen::Vector2d& point);
  // Splits at vertex v. Open: [0..v] keeps the id, [v..end] becomes a new contour whose id
  // is returned (nullopt when v is an end vertex: nothing to split). Closed: the contour
  // opens at v, keeping its id, starting and ending at copies of v; returns the same id.
  std::optional<int> Detach(int id, int vertex);
  // Adds points after the last vertex / before the first vertex of an open contour. Points
  // are given in contour order (for ExtendStart, the last given point joins the old start).
  void ExtendEnd(int id, const std::vector<Eigen::Vector2d>& points);
  void ExtendStart(int id, const std::vector<Eigen::Vector2d>& points);
  // Connects the end of `first` to the start of `second` through `bridge`. Both open. When
  // first == second the contour closes; otherwise `second` is merged into `first` and
  // removed. Returns the id of the result (first).
  int Join(int first, int second, const std::vector<Eigen::Vector2d>& bridge = {});

  enum class SpliceSide {
    kAttachStartAfterCut,  // result: [target start .. cut point] + attach
    kAttachEndBeforeCut,   // result: attach + [cut point .. target end]
  };
  struct SpliceResult {
    int joined = -1;      // the contour that now runs through the cut point
    int remainder = -1;   // the part of the target cut away (-1 if none)
  };
  // Cuts segment k of `target` at `point` and connects `attach` to the cut (attach is
  // consumed). Closed targets open at the cut point.
  SpliceResult Splice(int target, int segment, const Eigen::Vector2d& point, int attach, SpliceSide side);

  // Merges consecutive vertices closer than min_length (end vertices of open contours stay
  // put). Returns the number of vertices removed. Contours left with too few vertices are
  // removed (their id then no longer exists).
  int RemoveDegenerateSegments(int id, double min_length);
  // Removes vertices where the contour folds back on itself (the turn between the incoming
  // and outgoing segments exceeds max_turn radians; walls never fold back, so such a vertex
  // is an artefact of noise or a bad rough fit). Returns the number removed; contours left
  // with too few vertices are removed.
  int RemoveSpikes(int id, double max_turn);
  // Re-spaces the vertices at about nominal_length.
  void Resample(int id, double nominal_length);

  // --- checkpoints (map_checkpoint.h): the next id to hand out, and a map rebuilt with the
  // given contours (ids kept; the caller has validated them: unique, < next_id, sizes).
  int next_id() const { return next_id_; }
  void Restore(std::vector<Contour> contours, int next_id) {
    Clear();
    for (Contour& c : contours) {
      Reindex(c);
      const int id = c.id;
      contours_.emplace(id, std::move(c));
    }
    next_id_ = next_id;
  }

 private:
  Contour& Mutable(int id);
  void Reindex(const Contour& c);

  std::map<int, Contour> contours_;
  int next_id_ = 0;
  IncrementalSegmentIndex grid_;
};

}  // namespace minenav::mapper
