#include "planner/path_message.h"

#include <cmath>
#include <string>

#include "common/angle.h"
#include "common/file_io.h"
#include "common/node/conversions.h"

namespace minenav {

PathMessage PathFromLcm(const path_t& m, double turn_radius) {
  PathMessage out;
  out.utime = m.utime;
  out.request_id = m.request_id;
  out.feasible = m.feasible;
  out.status = m.status;
  if (m.num_segments < 0 || static_cast<size_t>(m.num_segments) != m.segments.size())
    throw InputError("path: num_segments " + std::to_string(m.num_segments) + " does not match the segments");
  out.path.start = FromLcm(m.start);
  Pose2 at = out.path.start;
  for (size_t k = 0; k < m.segments.size(); ++k) {
    const path_segment_t& s = m.segments[k];
    const std::string where = "path segment " + std::to_string(k) + ": ";
    if (s.motion < 0 || s.motion > 6) throw InputError(where + "unknown motion " + std::to_string(s.motion));
    if (!std::isfinite(s.speed) || s.speed < 0.0)
      throw InputError(where + "speed " + std::to_string(s.speed) + " m/s is not finite and >= 0");
    MotionPiece piece;
    piece.motion = static_cast<Motion>(s.motion);
    piece.end = FromLcm(s.end);
    const double dtheta = NormalizeAngle(piece.end.theta - at.theta);
    if (piece.motion == Motion::kTurnInPlace) {
      piece.amount = dtheta;
    } else if (IsArc(piece.motion)) {
      if (!(std::abs(s.radius - turn_radius) <= 0.01 * turn_radius))
        throw InputError(where + "arc radius " + std::to_string(s.radius) + " m is not the vehicle's " +
                         std::to_string(turn_radius) + " m");
      piece.radius = turn_radius;
      // The heading turns d * side * s / R (planner/motion.h): the arc length from the change.
      const double sign = DriveDirection(piece.motion) * TurnSide(piece.motion);
      double turned = sign * dtheta;
      if (turned < 0.0) turned += 2.0 * kPi;
      piece.amount = turned * turn_radius;
    } else {
      piece.amount = TranslationDistance(at, piece.end);
    }
    const Pose2 expected = PoseAfter(at, piece.motion, piece.amount, piece.radius);
    if (TranslationDistance(expected, piece.end) > 0.02 || HeadingDistance(expected, piece.end) > DegToRad(0.5))
      throw InputError(where + ToString(piece.motion) + " cannot reach its end pose from the previous one");
    out.path.pieces.push_back(piece);
    out.speeds.push_back(s.speed);
    at = piece.end;
  }
  return out;
}

path_t NoPathToLcm(int64_t request_id, int64_t utime, const std::string& status) {
  path_t m{};
  m.utime = utime;
  m.request_id = request_id;
  m.feasible = false;
  m.status = status;
  m.num_segments = 0;
  m.length = 0.0;
  return m;
}

path_t PathToLcm(const PlannedPath& path, int64_t request_id, int64_t utime, double speed, const std::string& status) {
  path_t m = NoPathToLcm(request_id, utime, status);
  m.feasible = true;
  m.start = ToLcm(path.start);
  for (const MotionPiece& p : path.pieces) {
    path_segment_t s{};
    s.motion = static_cast<int8_t>(p.motion);
    s.end = ToLcm(p.end);
    s.radius = p.radius;
    s.speed = speed;
    m.segments.push_back(s);
  }
  m.num_segments = static_cast<int32_t>(m.segments.size());
  m.length = path.Length();
  return m;
}

}  // namespace minenav
