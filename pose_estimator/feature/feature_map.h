#pragma once
// The line map as the feature predictor needs it (thesis 2.1.1, 2.1.3): the segments plus
// their endpoints merged into vertices, so that two segments sharing an endpoint form a
// corner. Built once per map.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace minenav {

struct FeatureMapOptions {
  double vertex_merge_distance = 0.01;  // m, endpoints closer than this are one vertex
};

class OptionScope;
// Declares every field of FeatureMapOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, FeatureMapOptions& o);

struct FeatureMap {
  std::vector<Segment> segments;
  std::vector<Eigen::Vector2d> vertices;            // merged endpoints
  std::vector<std::array<int, 2>> segment_vertices;  // vertex index of a and b per segment
  std::vector<std::vector<int>> vertex_segments;     // segments meeting at each vertex
};

// Builds the vertex graph. Segments shorter than vertex_merge_distance or with
// non-finite coordinates are dropped (they carry no feature); `dropped` counts them.
struct FeatureMapBuild {
  FeatureMap map;
  int dropped = 0;
};
FeatureMapBuild BuildFeatureMap(const std::vector<Segment>& segments,
                                const FeatureMapOptions& options = {});

}  // namespace minenav
