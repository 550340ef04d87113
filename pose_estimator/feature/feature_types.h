#pragma once
// Corner and line features of the feature-based pose estimator (thesis 2.1.2, Figure 2).
// A feature lives in one frame (the map frame after prediction, the sensor frame after
// extraction or after moving a predicted feature into the sensor frame) and carries the
// parameters the matcher and the minimiser need:
//   corner: vertex (x, y), concave angle, bisector orientation;
//   line:   perpendicular distance from the frame origin, orientation of that
//           perpendicular, length (of the visible or sensed piece).
// Lines are kept with the perpendicular pointing away from the frame origin (distance
// >= 0), so that a sensed line and the predicted line it matches use the same sign.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/pose2.h"

namespace minenav {

enum class FeatureType { kCorner, kLine };

struct Feature {
  FeatureType type = FeatureType::kCorner;

  // Corner (thesis 2.1.2). An occlusion corner is the visible end of a surface that hides
  // what lies behind it; one of its arms is the ray from the sensor through the vertex.
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m, vertex
  double concave_angle = 0.0;  // rad in [0, pi], the smaller angle between the two arms
  double bisector = 0.0;       // rad, orientation of the bisector of the concave angle
  bool occlusion = false;
  // m^2, extra variance of the vertex beyond what the fit gives: an occlusion corner's
  // true end lies somewhere within one angular step of the last point that saw it.
  double position_variance = 0.0;

  // Line: the set {p : p . (cos orientation, sin orientation) = distance}.
  double distance = 0.0;     // m, perpendicular distance from the frame origin, >= 0
  double orientation = 0.0;  // rad, orientation of the perpendicular
  double length = 0.0;       // m, of the visible / sensed piece
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  // m, piece ends in counter-clockwise
  Eigen::Vector2d end = Eigen::Vector2d::Zero();    //    order as seen from the origin

  // Bookkeeping.
  int num_points = 0;     // scan points behind a sensed feature (its weight), 0 for model
  double fit_rms = 0.0;   // m, RMS distance of those points from the fitted line(s)
  int map_segment = -1;   // model lines: index of the map segment
  int map_vertex = -1;    // model corners: index of the map vertex

  // Bearing from the frame origin used to order features as the scanner sweeps (rad in
  // (-pi, pi]): the vertex for a corner, the middle of the piece for a line.
  double Azimuth() const;
  double Range() const;  // m, from the frame origin to the vertex / the piece middle
  // Unit normal (cos orientation, sin orientation).
  Eigen::Vector2d Normal() const;
  // Signed distance of a point from a line feature, positive on the far side.
  double SignedDistance(const Eigen::Vector2d& p) const;
};

// A corner from its vertex and the unit directions of its two arms (pointing away from
// the vertex): fills concave angle and bisector.
Feature MakeCorner(const Eigen::Vector2d& vertex, const Eigen::Vector2d& arm1,
                   const Eigen::Vector2d& arm2, bool occlusion);

// A line through the piece start -> end (counter-clockwise from the origin), with the
// perpendicular chosen to point away from the origin.
Feature MakeLine(const Eigen::Vector2d& start, const Eigen::Vector2d& end);

// Re-expresses a feature given in frame `a` in frame `b`, where a_T_b is b's pose in a
// (EQ 6 of Appendix A.1 for the parameters). A line's perpendicular is flipped if needed to
// keep distance >= 0.
Feature TransformFeature(const Feature& f, const Pose2& a_T_b);

// Sorts features by Azimuth() (counter-clockwise from -pi).
void SortByAzimuth(std::vector<Feature>* features);

std::string ToString(const Feature& f);

}  // namespace minenav
