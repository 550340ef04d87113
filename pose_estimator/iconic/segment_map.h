#pragma once
// A line-segment map made safe for matching (thesis 3.1): non-finite, zero-length and
// duplicate segments are dropped before any correspondence structure is built, so the
// matchers never divide by a zero length or see two equally near copies of one wall.

#include <string>
#include <vector>

#include "common/geometry.h"

namespace minenav {

struct SegmentMapOptions {
  // Segments shorter than this are dropped (m). Default 1e-6 m: only truly degenerate ones.
  double min_segment_length = 1e-6;
  // Two segments whose endpoints coincide (either direction) within this are duplicates (m).
  double duplicate_tolerance = 1e-9;
};

class OptionScope;
// Declares every field of SegmentMapOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, SegmentMapOptions& o);

struct SegmentMap {
  std::vector<Segment> segments;  // the cleaned segments
  int dropped_nonfinite = 0;
  int dropped_zero_length = 0;
  int dropped_duplicates = 0;
  // Empty when the map is usable, else a one-line reason ("map has no usable segments").
  std::string problem;
};

SegmentMap PrepareSegmentMap(const std::vector<Segment>& raw, const SegmentMapOptions& options = {});

}  // namespace minenav
