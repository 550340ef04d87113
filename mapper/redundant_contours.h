#pragma once
// Removal of redundant contours (thesis 7.2.4, "some of this is best fixed by removing
// redundant contours"). When a wall is mapped twice, e.g. by scans at both ends of a loop
// whose poses drifted apart, the two contours lie close together and face the same way.
// Each scan then matches its own copy (nearest wins) and concurrent refinement can never
// pull the loop together. This removes the vertices of the newer contour (higher id) that
// lie within `distance` of a segment of an older one facing the same way, splitting the
// newer contour around them; the scans that built it then correspond to the older one.

#include "common/config.h"
#include "mapper/contour_map.h"

namespace minenav::mapper {

struct RedundantContourOptions {
  // m; a vertex this close to another contour's segment may be redundant. Larger than the
  // pose drift to be closed, smaller than the gap between distinct same-facing walls.
  double distance = 0.4;
  // Cosine of the largest angle between the two contours' normals (same facing).
  double min_alignment = 0.8;
  // m; only runs of redundant vertices at least this long (along the contour) are removed,
  // so a small object standing close to a wall (a post, a crib block) is not taken for a
  // copy of the wall, nor the wall for a copy of it.
  double min_run_length = 1.0;
};

// Declares every field of `o` under `scope` (unit, default, range, why): config keys and flags.
void DeclareOptions(OptionScope scope, RedundantContourOptions& o);

// Returns the number of vertices removed.
int RemoveRedundantContours(ContourMap& map, const RedundantContourOptions& options = {});

}  // namespace minenav::mapper
