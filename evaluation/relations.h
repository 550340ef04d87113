#pragma once
// The relation-based SLAM error metric of Kuemmerle et al., "On measuring the accuracy of
// SLAM algorithms", Autonomous Robots 27(4), 2009, in the form of Freiburg's
// metricEvaluator (shared/datasets/SOURCES.md, issue #7). A relation is a measured robot
// motion between two times t1 and t2, in the frame of the robot at t1. For each relation:
//   P(t)  = the estimated robot pose whose time is nearest t, when within
//           options.max_time_gap; else that nearest estimate moved on by the odometry
//           from its time to t: P(t) = P(te) * O(te)^-1 * O(t) (O interpolated in time);
//           a relation whose times cannot be served either way is skipped and counted;
//   delta = P(t1)^-1 * P(t2);
//   translational error = |t_delta - t_delta*| (m);
//   rotational error    = |wrap(theta_delta - theta_delta*)| (rad, reported in degrees).
// The score is N and, for the absolute and the squared errors, their mean and sample
// standard deviation (divisor N - 1): translation in m and m^2, rotation in deg and deg^2.
// Plain C++ (no LCM), so benchmarks can score poses in-process.

#include <cstdint>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/pose2.h"

namespace minenav {

// One line of a relations file: "t1 t2 x y z roll pitch yaw" (s, s, m, m, m, rad, rad, rad).
// z, roll and pitch are 0 in the 2D files and ignored.
struct Relation {
  int64_t utime1 = 0;  // us
  int64_t utime2 = 0;  // us
  Pose2 delta;         // robot at t2 in the frame of the robot at t1 (yaw wrapped)
};

// Throws InputError naming the source, the line and the field for a malformed line.
// Blank lines and lines starting with '#' are skipped.
std::vector<Relation> ParseRelations(const std::string& text, const std::string& source_name);
std::vector<Relation> LoadRelations(const std::string& path);

struct RelationOptions {
  // s. An estimate at most this far from a relation's time is used as the pose at that
  // time; farther ones are moved on with odometry (metricEvaluator uses 0.1 s).
  double max_time_gap = 0.1;
  // s. Odometry is interpolated between readings at most 2 * this apart, or taken from
  // the end reading when the time is within this of it; else the relation is skipped.
  // Intel's ODOM stream pauses for up to 2.3 s while the robot stands: 1 s would skip 51
  // of its 2984 relations.
  double max_odometry_gap = 5.0;
};

// Mean and sample standard deviation (divisor N - 1; 0 when N < 2).
struct ErrorStatistic {
  double mean = 0.0;
  double std = 0.0;
};

struct RelationErrorEntry {
  Relation relation;
  double translation_error = 0.0;  // m
  double rotation_error = 0.0;     // rad, >= 0
  bool odometry_corrected = false;  // one of the two poses came through odometry
};

struct RelationScore {
  bool ok = false;            // at least one relation was scored
  std::string reason;         // why not, when !ok
  int64_t relations = 0;      // in the file
  int64_t n = 0;              // scored
  int64_t skipped = 0;        // no estimate within reach (and no usable odometry)
  int64_t odometry_corrected = 0;  // scored relations that needed odometry
  int64_t not_estimates = 0;  // rows of `estimates` left out: not converged (PoseStatus)
  ErrorStatistic translation;         // m
  ErrorStatistic translation_squared; // m^2
  ErrorStatistic rotation;            // deg
  ErrorStatistic rotation_squared;    // deg^2
  std::vector<RelationErrorEntry> entries;  // one per scored relation, in file order
};

// Scores `estimates` (any order; robot poses keyed by utime, e.g. a poses CSV; rows whose
// status is not an estimate are left out and counted) against `relations`. `odometry` (any
// order; may be empty) corrects estimates farther than max_time_gap from a relation time.
// Never throws for bad data: an empty result says why.
RelationScore ScoreRelations(const std::vector<Relation>& relations, const std::vector<StampedPose>& estimates,
                             const std::vector<StampedPose>& odometry, const RelationOptions& options = {});

// Mean and sample standard deviation of values.
ErrorStatistic MeanAndSampleStd(const std::vector<double>& values);

}  // namespace minenav
