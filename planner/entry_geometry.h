#pragma once
// The geometry of an entry to advance (thesis 6.2.1: "based on the coarse geometry of the
// problem"): the face straight ahead of a hint, the entry's walls left and right of the way
// to it, its width, its axis and how far the face is off square to it.
//
//   face hint   a ray from the hint point along the direction of advance; the first wall it
//               meets within max_face_distance is on the face (a frontier first: the face is
//               in unexplored space; nothing: the hint points at nothing);
//   side walls  from points every ray_spacing back along the ray (up to wall_search_length,
//               never through a wall), rays to the left and right; hits on walls running
//               within 35 deg of the ray, at most max_half_width away, the side's outliers
//               (over 1.5 m from its median offset: a crosscut's far wall) dropped. Each side
//               needs min_wall_hits, else no entry is found. Least-squares lines through each
//               side give the entry's axis (their mean direction);
//   face        rays along the axis from 2 m before the face, every ray_spacing across the
//               entry; hits on walls running within max_square_angle + 20 deg of across the
//               axis, within 1 m of their median depth; a total-least-squares line through
//               them. The cuts are squared to it (the cutter turns to the face's normal).
//
// Two frames, both with their origin at the middle of the face: the ENTRY FRAME (x along
// the entry's axis towards the face, y to the left: the ribs run along x) and the FACE FRAME
// (x along the face's normal into the coal, y to the left: the face runs along y; it is the
// entry frame turned by face_angle). The ribs and the face are measured exactly on the
// segments that were hit (not just at the ray hits): jittered walls stick out between rays.
//
// Plain C++: no LCM, clock or I/O.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"
#include "planner/task.h"
#include "planner/task_map.h"
#include "tracker/cutter.h"

namespace minenav {

class OptionScope;

struct EntryOptions {
  double max_face_distance = 15.0;   // m: the face is looked for this far ahead of the hint. Default 15.
  double wall_search_length = 20.0;  // m: the entry's walls are looked for this far back from the face. Default 20.
  double max_half_width = 8.0;       // m: side walls farther than this from the ray are not the entry's. Default 8.
  double ray_spacing = 0.25;         // m between the rays along the walls and across the face. Default 0.25.
  // rad: the face's normal at most this far off the entry's axis (the cutter's
  // max_square_angle: it refuses more). Default 0.6.
  double max_square_angle = CutterOptions{}.max_square_angle;
  int min_wall_hits = 4;  // rays that must hit each side wall. Default 4.
};

// "" when usable, else one line naming the option.
std::string ValidateOptions(const EntryOptions& options);
// max_face_distance, wall_search_length, max_half_width, ray_spacing, max_square_angle, min_wall_hits.
void DeclareOptions(OptionScope scope, EntryOptions& options);

// A straight line y = a + b x in the face frame.
struct WallLine {
  double a = 0.0, b = 0.0;
  double At(double x) const { return a + b * x; }
};

struct EntryGeometry {
  Pose2 entry_frame;  // world_T_entry
  Pose2 face_frame;   // world_T_face = entry_frame * (0, 0, face_angle)
  Segment face;       // map frame: the fitted face across the entry, right end to left end (free space on its left)
  double axis = 0.0;  // rad, map frame: the entry's direction towards the face
  double face_angle = 0.0;       // rad: the face's normal less the axis (0 = square; positive: normal turned left)
  double width = 0.0;            // m: the entry's width across its axis (median over the rays that hit both ribs)
  double face_distance = 0.0;    // m from the hint to the face along the hint's ray
  WallLine left_fit, right_fit;  // entry frame: least-squares lines through each rib's hits
  // Entry frame: the segments each side's rays hit, and the ray hits (pictures, tests).
  std::vector<Segment> left_wall, right_wall;
  std::vector<Eigen::Vector2d> left_hits, right_hits;
  // Face frame: the face's segments and the ray hits on them.
  std::vector<Segment> face_segments;
  std::vector<Eigen::Vector2d> face_hits;

  // m, entry frame: the least y of the left rib over x in [x0, x1] (its segments there, and
  // its fitted line at x0 and x1: beyond the rib's end, e.g. across a crossing, the line goes on).
  double LeftLimit(double x0, double x1) const;
  // m, entry frame: the greatest y of the right rib over x in [x0, x1].
  double RightLimit(double x0, double x1) const;
  // m, face frame: the nearest x of the face over y in [y0, y1] (0 where no face segment is).
  double FaceLimit(double y0, double y1) const;
  // Map poses and points at face-frame coordinates (poses heading along the face's normal).
  Pose2 FacePose(double x, double y) const { return face_frame * Pose2(x, y, 0.0); }
  Eigen::Vector2d FacePoint(double x, double y) const { return face_frame * Eigen::Vector2d(x, y); }
  // Face-frame coordinates of an entry-frame point, and back.
  Eigen::Vector2d EntryToFace(const Eigen::Vector2d& p) const { return Pose2(0.0, 0.0, face_angle).inverse() * p; }
  Eigen::Vector2d FaceToEntry(const Eigen::Vector2d& p) const { return Pose2(0.0, 0.0, face_angle) * p; }
};

struct EntryResult {
  std::optional<EntryGeometry> entry;
  std::string reason;  // one line when there is no entry
};

// The entry whose face lies ahead of `hint` along `direction` (rad) in `map`.
EntryResult FindEntry(const TaskMap& map, const Eigen::Vector2d& hint, double direction, const EntryOptions& options);

}  // namespace minenav
