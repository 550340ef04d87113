#pragma once
// A contour (thesis 4.1.1): a polyline with short segments and no gaps, open or closed.
//
// Orientation convention (the whole mapper relies on it): walking from points[k] to
// points[k + 1], the free space the contour was sensed from lies on the LEFT. Seen from
// the sensor, vertices follow increasing bearing, i.e. counter-clockwise about the sensor;
// a room seen from inside is a counter-clockwise polygon, a pillar seen from outside is a
// clockwise one. A closed contour's last segment runs from points.back() to points.front().

#include <Eigen/Core>
#include <vector>

#include "common/geometry.h"

namespace minenav::mapper {

struct Contour {
  int id = -1;            // stable for the life of the contour in its map
  bool closed = false;
  std::vector<Eigen::Vector2d> points;  // m, world frame

  int NumPoints() const { return static_cast<int>(points.size()); }
  int NumSegments() const {
    const int n = NumPoints();
    if (n < 2) return 0;
    return closed && n >= 3 ? n : n - 1;
  }
  // Segment k runs from vertex k to vertex (k + 1) mod n.
  int SegmentStart(int k) const { return k; }
  int SegmentEnd(int k) const { return (k + 1) % NumPoints(); }
  Segment GetSegment(int k) const { return Segment(points[SegmentStart(k)], points[SegmentEnd(k)]); }
  double Length() const { return PolylineLength(points, closed); }
};

// A reference to one segment of one contour.
struct SegmentRef {
  int contour = -1;
  int segment = -1;
  bool operator==(const SegmentRef&) const = default;
  auto operator<=>(const SegmentRef&) const = default;
};

// Vertices at about `nominal_length` spacing along the polyline (arc length), keeping the
// end points of an open polyline. Closed polylines start at points[0].
std::vector<Eigen::Vector2d> ResamplePolyline(const std::vector<Eigen::Vector2d>& points, bool closed,
                                              double nominal_length);

// Picks vertices among `points` (in order) so that consecutive vertices are at least
// `min_length` apart: the rough fit of 4.4.1. The first and last points are kept; a last
// vertex crowding the end point is dropped.
std::vector<Eigen::Vector2d> PickVertices(const std::vector<Eigen::Vector2d>& points, double min_length);

}  // namespace minenav::mapper
