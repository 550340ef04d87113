#pragma once
// Feature matching (thesis 2.1.5): pairs sensed features with predicted map features.
//   Unary bounds (where a feature is, given the pose is within poserr and angerr):
//     corner bearing within angerr, corner range within poserr, the angular extents of a
//     sensed and a model line overlap allowing a rotation of angerr.
//   Unary properties: concave angle within concerr, bisector orientation within angerr,
//     line orientation within angerr, line distance within poserr + disterr. (Ours: a
//     sensed line is not longer than the visible model piece plus disterr.)
//   Binary constraints between two pairs (independent of the pose): corner-corner
//     distances agree within bindisterr, line-line orientation differences within
//     binangerr, a corner lies on the same side of and as far from a line within
//     bindisterr. (Ours, same tolerances: two parallel lines also keep their separation.)
//   Search: pairs are ordered by sensed feature, the order the scanner sweeps; a set of
//     pairs is consistent if it keeps the sweep order of the model features too (cyclic,
//     so an initial heading error that moves the cut at -pi does not matter) and every two
//     pairs in it satisfy the binary constraints. A depth-first search over the ordered
//     pair list grows sets; the longest pairwise-consistent sequences into and out of each
//     pair bound what a branch can still reach, which cuts fruitless branches. The largest
//     consistent set wins (ties: more scan points behind the sensed features).
// Deviations from the text, both to honour the stated bounds: bearings of corners and
// extents of lines are widened by atan(poserr / range), since a position error also turns
// bearings; every pair of a set is checked, not only the two preceding ones.
#include <vector>

#include "common/angle.h"
#include "pose_estimator/feature/feature_types.h"

namespace minenav {

struct MatchingOptions {
  double angerr = DegToRad(5.0);      // rad, bound on the initial heading error
  double poserr = 1.0;                // m, bound on the initial position error
  double concerr = DegToRad(10.0);    // rad, tolerance on concave angles
  double disterr = 0.5;               // m, tolerance on line distances (beyond poserr)
  double bindisterr = 0.5;            // m, tolerance of the binary distance constraints
  double binangerr = DegToRad(5.0);   // rad, tolerance of the binary angle constraints
  int max_search_nodes = 200000;      // bound on the depth-first search (time guard)
};

class OptionScope;
// Declares every field of MatchingOptions under `scope` (unit, meaning, range).
void DeclareOptions(OptionScope scope, MatchingOptions& o);

struct FeaturePair {
  int sensed = 0;  // index into the sensed list
  int model = 0;   // index into the model list
};

// The feature pairing of the matching stage (2.1.5); not a pose: see FeaturePoseResult.
struct FeatureMatchResult {
  std::vector<FeaturePair> pairs;  // the largest consistent set, in sweep order
  int candidate_pairs = 0;         // pairs that passed the unary constraints
  int search_nodes = 0;
  bool search_complete = true;     // false if max_search_nodes cut the search short
};

// Both lists in the sensor frame (model features moved there with the initial estimate by
// TransformFeature), each ordered by azimuth.
bool UnaryConsistent(const Feature& sensed, const Feature& model, const MatchingOptions& options);
bool BinaryConsistent(const Feature& sensed1, const Feature& model1, const Feature& sensed2,
                      const Feature& model2, const MatchingOptions& options);
FeatureMatchResult MatchFeatures(const std::vector<Feature>& sensed, const std::vector<Feature>& model,
                                 const MatchingOptions& options = {});

}  // namespace minenav
