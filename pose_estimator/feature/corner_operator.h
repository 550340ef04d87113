#pragma once
// The corner operator of thesis 2.1.4 (Figure 4): a template of two arms of a given length
// that slides along a piece of scan one point at a time. At each point both arms are fit
// to the scan points within arm_length on either side by an incremental line fitter; if
// both are straight and the angle between them lies in an interval around 90 degrees, the
// point is a corner candidate. Of each run of neighbouring candidates the one whose arms
// fit best is kept, and the corner is placed at the intersection of its two arm lines.
#include <Eigen/Core>
#include <vector>

#include "common/angle.h"

namespace minenav {

struct CornerOperatorOptions {
  double arm_length = 0.8;                    // m, length of each arm of the template
  int min_arm_points = 5;                     // points an arm needs to be fit
  double min_arm_extent = 0.7;                // fraction of arm_length an arm must span
  double min_corner_angle = DegToRad(60.0);   // rad, interval of accepted angles between
  double max_corner_angle = DegToRad(120.0);  // rad, the arms ("around 90 degrees")
  double max_arm_rms = 0.15;                  // m, straightness of each arm
  // rad: an arm closer than this to the ray from the sensor through the vertex is seen at
  // a grazing angle or is a streak of mixed pixels at an occlusion (2.2): no corner there.
  // Points are in the sensor frame, so the ray is the vertex's direction.
  double min_arm_to_ray_angle = DegToRad(15.0);
  // m, as a fraction of arm_length: closer corners are one corner (the better fit wins)
  double min_corner_separation = 0.5;
};

class OptionScope;
// Declares every field of CornerOperatorOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, CornerOperatorOptions& o);

struct CornerCandidate {
  int index = 0;  // index into the piece of the point the operator was centred on
  Eigen::Vector2d vertex = Eigen::Vector2d::Zero();  // intersection of the two arm lines
  Eigen::Vector2d arm_before = Eigen::Vector2d::UnitX();  // unit, from vertex toward earlier points
  Eigen::Vector2d arm_after = Eigen::Vector2d::UnitY();   // unit, toward later points
  int num_points = 0;   // points on both arms
  double fit_rms = 0.0;  // m, RMS of both arm fits together
};

// `piece`: consecutive scan points of one unbroken piece, in scan order.
std::vector<CornerCandidate> ApplyCornerOperator(const std::vector<Eigen::Vector2d>& piece,
                                                 const CornerOperatorOptions& options);

}  // namespace minenav
