#pragma once
// Small segment maps for the planner's tests, built inline: a room, a corridor, a crossing
// of two 6 m entries (room-and-pillar), two rooms with no door between them.

#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "common/segment_index.h"
#include "planner/clearance_field.h"
#include "planner/footprint.h"
#include "planner/motion.h"
#include "planner/testing/path_checker.h"

namespace minenav::planner_test {

// The closed rectangle [x0, x1] x [y0, y1].
inline void AddBox(std::vector<Segment>& m, double x0, double y0, double x1, double y1) {
  m.push_back({x0, y0, x1, y0});
  m.push_back({x1, y0, x1, y1});
  m.push_back({x1, y1, x0, y1});
  m.push_back({x0, y1, x0, y0});
}

// The same polygon as `box` (a rectangle) with a fifth vertex in the middle of its front edge
// (x > 0): not a 4-corner box, so the collision checker takes its general polygon path.
inline Footprint WithFrontMidpoint(const Footprint& box) {
  Footprint five = box;
  for (size_t i = 0; i < box.vertices.size(); ++i) {
    const Eigen::Vector2d& p = box.vertices[i];
    const Eigen::Vector2d& q = box.vertices[(i + 1) % box.vertices.size()];
    if (p.x() > 0.0 && q.x() > 0.0) {
      five.vertices.insert(five.vertices.begin() + static_cast<std::ptrdiff_t>(i) + 1, 0.5 * (p + q));
      break;
    }
  }
  return five;
}

// What a FootprintCollisionChecker is built on: `walls` inside the box [-20, 20]^2, their
// index and their clearance field (0.2 m cells, capped at 8 m).
struct CheckerWorld {
  std::vector<Segment> walls;
  StaticSegmentIndex index;
  ClearanceField field;
  explicit CheckerWorld(std::vector<Segment> w)
      : walls(Boxed(std::move(w))),
        index(walls),
        field(walls, GridFrame::Covering(Eigen::Vector2d(-20, -20), Eigen::Vector2d(20, 20), 0.2, 0.0), 8.0) {}

 private:
  static std::vector<Segment> Boxed(std::vector<Segment> w) {
    AddBox(w, -20, -20, 20, 20);
    return w;
  }
};

inline std::vector<Segment> Room(double w, double h) {
  std::vector<Segment> m;
  AddBox(m, 0, 0, w, h);
  return m;
}

// A corridor `width` wide from x = 0 to x = length, centre line y = 0, closed at both ends.
inline std::vector<Segment> Corridor(double length, double width) {
  std::vector<Segment> m;
  AddBox(m, 0, -0.5 * width, length, 0.5 * width);
  return m;
}

// A crossing of two entries `width` wide along x and y (centre lines through the origin),
// each reaching `arm` from the centre, among four pillars; closed at the arms' ends.
inline std::vector<Segment> Crossing(double width, double arm) {
  const double h = 0.5 * width;
  std::vector<Segment> m;
  // The four pillar corners: walls along the arms.
  for (const int sx : {1, -1})
    for (const int sy : {1, -1}) {
      m.push_back({sx * h, sy * h, sx * arm, sy * h});
      m.push_back({sx * h, sy * h, sx * h, sy * arm});
    }
  m.push_back({arm, -h, arm, h});
  m.push_back({-arm, -h, -arm, h});
  m.push_back({-h, arm, h, arm});
  m.push_back({-h, -arm, h, -arm});
  return m;
}

// The checker's settings for `polygon` (vehicle frame) at `clearance` (m), the polygon sampled
// every `sample_step` m.
inline testing::PathCheckSettings CheckSettings(const std::vector<Eigen::Vector2d>& polygon, double clearance,
                                                double sample_step = 0.02) {
  testing::PathCheckSettings s;
  s.polygon = polygon;
  s.clearance = clearance;
  s.sample_step = sample_step;
  return s;
}

// The planner's pieces as the checker sees them (motion code and end pose only).
inline std::vector<testing::CheckedPiece> AsChecked(const PlannedPath& path) {
  std::vector<testing::CheckedPiece> c;
  for (const MotionPiece& p : path.pieces) c.push_back({static_cast<int>(p.motion), p.end});
  return c;
}

}  // namespace minenav::planner_test
