#pragma once
// Correspondence determination (thesis 3.1.1): each scan point is paired with the map
// segment nearest to it, where the distance to a segment is the distance to its interior
// (perpendicular, "point-to-line") or to its nearer endpoint ("point-to-point"). Points
// farther than a threshold from every segment get no pairing.
//
// Three implementations share this interface so they can be compared (Table 9):
//   kBruteForce   O(MN), every segment per point (Cox 1991)           brute_force_correspondence.h
//   kGridSearch   segments bucketed in a grid, every cell within the threshold visited
//                 (a simplified Gonzalez 1992)                          grid_search_correspondence.h
//   kLookupTable  the thesis's table: a grassfire-grown grid whose cells hold the short
//                 list of possibly nearest segments; one cell per point  lookup_table_correspondence.h

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace minenav {

struct SegmentMatch {
  int segment = -1;  // index into the map's segments; -1 = no segment within the threshold
  double distance = 0.0;  // m, point to segment
  SegmentRegion region = SegmentRegion::kInterior;
  Eigen::Vector2d closest = Eigen::Vector2d::Zero();  // nearest point on the segment

  bool matched() const { return segment >= 0; }
};

// Which segment endpoints end a polyline (no other segment starts or ends there): bit 0 for
// a, bit 1 for b. A point nearest to such an end lies beyond the mapped surface (an
// unmapped wall, the edge of another scan's view); pairing it with the end would pull the
// estimate along the wall, so the matchers can skip those pairs (reject_open_ends).
std::vector<uint8_t> ComputeOpenEnds(const std::vector<Segment>& segments);
inline bool IsOpenEnd(const std::vector<uint8_t>& open_ends, int segment, SegmentRegion region) {
  const uint8_t f = open_ends[static_cast<size_t>(segment)];
  return (region == SegmentRegion::kStartPoint && (f & 1)) || (region == SegmentRegion::kEndPoint && (f & 2));
}

class CorrespondenceSearch {
 public:
  virtual ~CorrespondenceSearch() = default;
  // ComputeOpenEnds(segments()), computed once.
  const std::vector<uint8_t>& open_ends() const {
    if (open_ends_.size() != segments().size()) open_ends_ = ComputeOpenEnds(segments());
    return open_ends_;
  }
  // The nearest segment to p (map frame) no farther than max_distance (m). Ties go to the
  // lower segment index so that all implementations agree exactly.
  virtual SegmentMatch Nearest(const Eigen::Vector2d& p, double max_distance) const = 0;
  virtual const std::vector<Segment>& segments() const = 0;
  virtual const char* name() const = 0;

 private:
  mutable std::vector<uint8_t> open_ends_;
};

enum class CorrespondenceMethod { kBruteForce, kGridSearch, kLookupTable };
const char* ToString(CorrespondenceMethod method);
// "brute", "grid", "lookup"; returns false on anything else.
bool ParseCorrespondenceMethod(const std::string& text, CorrespondenceMethod* out);

struct CorrespondenceOptions {
  CorrespondenceMethod method = CorrespondenceMethod::kLookupTable;
  // Grid cell size for grid search and lookup table (m). 0 = choose from the map: half
  // the median segment length, clamped to [0.03, 1] m, which keeps lists short (3.1.1).
  double cell_size = 0.0;
  // How far from the map the lookup table is grown (m): points farther than this never
  // match. It must cover the largest correspondence threshold used (the initial error).
  double max_distance = 3.0;
};

class OptionScope;
// Declares every field of CorrespondenceOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, CorrespondenceOptions& o);

// Builds the chosen structure over `segments` (which should be cleaned by
// PrepareSegmentMap first: zero-length and duplicate segments are tolerated but waste time).
std::unique_ptr<CorrespondenceSearch> MakeCorrespondenceSearch(std::vector<Segment> segments,
                                                               const CorrespondenceOptions& options);

// Nearest segment for every point (out is resized to points.size()).
void FindCorrespondences(const CorrespondenceSearch& search, const std::vector<Eigen::Vector2d>& points,
                         double max_distance, std::vector<SegmentMatch>* out);


// Default cell size for a map (m): half the median segment length clamped to [0.03, 1].
double ChooseCellSize(const std::vector<Segment>& segments);

// Most cells a correspondence grid may have (each holds a few candidate lists): bounds the
// memory one map message can cost (issue 11: one 20 km segment must not allocate GBs).
inline constexpr double kMaxGridCells = 4e6;
// Most cells the walls and their reach may cover (the lookup table's grassfire visits each
// with its lists): bounds the work one map message can cost. A random-seed fuzz run found a
// LINE_MAP of 11 short walls and one 127 km long that kept the grid within kMaxGridCells at
// 1 m cells yet grew 890,000 cells: 0.52 s to build in the release build, over 40 s in the
// fuzz build. 2^17 covers 18 km of wall at 1 m cells (reach 3 m), 5 km at 0.5 m and 1.3 km
// at 0.25 m: a mine section's map keeps the cell it chose; a larger map gets coarser cells
// (longer lists, the same answers). That map now costs 0.1 s in the release build.
inline constexpr double kMaxBandCells = 131072.0;
// The cells within `margin` of the walls at `cell` m, as the table grows them: per segment
// the cells along it times the band across it.
double BandCells(const std::vector<Segment>& segments, double cell, double margin);
// `cell`, or the smallest larger cell that keeps the grid over `segments` (grown by
// `margin` m on every side) within kMaxGridCells and the band within
// max(kMaxBandCells, 9 per segment) (3 per segment is the least any cell gives).
double CellSizeWithinBudget(const std::vector<Segment>& segments, double cell, double margin);

// A segment with what every distance query needs precomputed; all three searches use the
// same kernel so that Table 9 compares search strategies, not arithmetic.
struct PreparedSegment {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d d = Eigen::Vector2d::Zero();  // b - a
  double inv_length2 = 0.0;                     // 1 / |d|^2, 0 for a degenerate segment

  explicit PreparedSegment(const Segment& s)
      : a(s.a), d(s.b - s.a), inv_length2(d.squaredNorm() > 0.0 ? 1.0 / d.squaredNorm() : 0.0) {}

  double SquaredDistance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d ap = p - a;
    double t = ap.dot(d) * inv_length2;
    t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
    return (ap - t * d).squaredNorm();
  }
};
std::vector<PreparedSegment> PrepareSegments(const std::vector<Segment>& segments);

// The full match (region, closest point) of p against one prepared segment.
inline SegmentMatch MakeMatch(const Eigen::Vector2d& p, const PreparedSegment& s, int index, double d2) {
  SegmentMatch m;
  m.segment = index;
  m.distance = std::sqrt(d2);
  const double t = (p - s.a).dot(s.d) * s.inv_length2;
  if (t <= 0.0) {
    m.region = SegmentRegion::kStartPoint;
    m.closest = s.a;
  } else if (t >= 1.0) {
    m.region = SegmentRegion::kEndPoint;
    m.closest = s.a + s.d;
  } else {
    m.region = SegmentRegion::kInterior;
    m.closest = s.a + t * s.d;
  }
  return m;
}

}  // namespace minenav
