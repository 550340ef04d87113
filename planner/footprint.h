#pragma once
// The vehicle's outline: a simple polygon in the vehicle frame (x forward, y left, origin at
// the pose the planner plans for). The default miner is a rectangle 3.3 m wide and 10 m long
// centred on the pose.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/pose2.h"

namespace minenav {

struct Footprint {
  std::vector<Eigen::Vector2d> vertices;  // m, vehicle frame, counter-clockwise

  // width (m, along y) x length (m, along x), centred on the pose.
  static Footprint Rectangle(double width, double length);
  // The polygon placed at `pose` (m, map frame).
  std::vector<Eigen::Vector2d> At(const Pose2& pose) const {
    std::vector<Eigen::Vector2d> placed;
    placed.reserve(vertices.size());
    for (const Eigen::Vector2d& v : vertices) placed.push_back(pose * v);
    return placed;
  }
};

// "" when usable, else one line: at least 3 finite vertices, non-zero area, the pose's
// origin inside, no two edges crossing. Clockwise polygons are accepted (Normalized fixes them).
std::string ValidateFootprint(const Footprint& footprint);
// The same polygon counter-clockwise.
Footprint Normalized(Footprint footprint);

// m: radius of the largest circle about the origin inside the polygon (the distance from
// the origin to the nearest edge; the polygon must contain the origin).
double InscribedRadius(const Footprint& footprint);
// m: radius of the smallest circle about the origin that holds the polygon.
double CircumscribedRadius(const Footprint& footprint);

// Is p (vehicle frame) inside or on the polygon? (Crossing number.)
bool PolygonContains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

// A footprint file, JSON {"footprint": [[x, y], ...]} (m, vehicle frame); throws InputError
// with one line naming the source.
Footprint ParseFootprintJson(const std::string& text, const std::string& source_name);

}  // namespace minenav
