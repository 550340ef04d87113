#include "planner/entry_geometry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "common/angle.h"
#include "common/config.h"
#include "common/segment_index.h"

namespace minenav {
namespace {

// A side wall runs within this of the hint's ray (jittered walls wander a few degrees; a
// crosscut's pillar face runs across it).
constexpr double kWallAngle = DegToRad(35.0);
// A face runs within max_square_angle + this of across the axis.
constexpr double kFaceAngleSlack = DegToRad(20.0);
// m: a side hit this far from its side's median offset is not the entry's wall (a crosscut's
// far side, a pillar's corner across a crossing).
constexpr double kWallOutlier = 1.5;
// m: a face hit this far from the median depth of the face hits is not the face.
constexpr double kFaceOutlier = 1.0;
// m: the rays across the face keep this far from the walls' lines (the face up to its
// corners: a drum at the rib meets it there).
constexpr double kFaceRayMargin = 0.02;
// m: the rays across the face are at most this far apart (a drum's standoff is measured on them).
constexpr double kFaceRaySpacing = 0.1;
constexpr int kMinFaceHits = 3;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Least-squares y = a + b x (b = 0 when the points do not spread in x).
WallLine FitLine(const std::vector<Eigen::Vector2d>& points) {
  WallLine line;
  if (points.empty()) return line;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double sxx = 0.0, sxy = 0.0;
  for (const Eigen::Vector2d& p : points) {
    sxx += (p.x() - mean.x()) * (p.x() - mean.x());
    sxy += (p.x() - mean.x()) * (p.y() - mean.y());
  }
  line.b = sxx > 1e-9 ? sxy / sxx : 0.0;
  line.a = mean.y() - line.b * mean.x();
  return line;
}

// Angle (rad, in [0, pi/2]) between the segment's line and the direction `dir` (unit).
double AngleTo(const Segment& s, const Eigen::Vector2d& dir) {
  const double len = s.length();
  if (len <= 0.0) return kPi / 2.0;
  return std::acos(std::min(1.0, std::abs(s.direction().dot(dir)) / len));
}

// The values of coordinate `other` at the ends of the part of `s` whose coordinate `along`
// lies in [lo, hi]; false when no part does.
bool ClippedValues(const Segment& s, int along, double lo, double hi, double& v0, double& v1) {
  const int other = 1 - along;
  const double p0 = s.a[along], p1 = s.b[along];
  if (std::max(p0, p1) < lo || std::min(p0, p1) > hi) return false;
  if (std::abs(p1 - p0) < 1e-12) {
    v0 = s.a[other];
    v1 = s.b[other];
    return true;
  }
  auto at = [&](double c) { return s.a[other] + (s.b[other] - s.a[other]) * (c - p0) / (p1 - p0); };
  v0 = at(std::clamp(p0, lo, hi));
  v1 = at(std::clamp(p1, lo, hi));
  return true;
}

Segment Transformed(const Pose2& t, const Segment& s) { return {t * s.a, t * s.b}; }

std::string Deg(double rad) { return FixedNumber(RadToDeg(rad), 1) + " deg"; }
std::string Point(const Eigen::Vector2d& p) { return "(" + FixedNumber(p.x()) + ", " + FixedNumber(p.y()) + ")"; }

// The least (sign +1) or greatest (sign -1) value of the other coordinate over the parts of
// `segments` whose coordinate `along` lies in [lo, hi], and `start`.
double Extreme(const std::vector<Segment>& segments, int along, double lo, double hi, double sign, double start) {
  double best = start;
  for (const Segment& s : segments) {
    double v0 = 0.0, v1 = 0.0;
    if (ClippedValues(s, along, lo, hi, v0, v1)) best = sign * std::min({sign * best, sign * v0, sign * v1});
  }
  return best;
}

}  // namespace

std::string ValidateOptions(const EntryOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.max_face_distance)) return "entry.max_face_distance must be > 0";
  if (!positive(o.wall_search_length)) return "entry.wall_search_length must be > 0";
  if (!positive(o.max_half_width)) return "entry.max_half_width must be > 0";
  if (!positive(o.ray_spacing) || o.ray_spacing > 2.0) return "entry.ray_spacing must be in (0, 2] m";
  if (!std::isfinite(o.max_square_angle) || o.max_square_angle <= 0.0 || o.max_square_angle >= kPi / 2.0)
    return "entry.max_square_angle must be in (0, pi/2) rad";
  if (o.min_wall_hits < 2) return "entry.min_wall_hits must be at least 2";
  return "";
}

void DeclareOptions(OptionScope s, EntryOptions& o) {
  s.AddDouble("max_face_distance", &o.max_face_distance, "m", "the face is looked for this far ahead of the hint", 0.1,
              1000.0);
  s.AddDouble("wall_search_length", &o.wall_search_length, "m",
              "the entry's walls are looked for this far back from the face", 0.1, 1000.0);
  s.AddDouble("max_half_width", &o.max_half_width, "m",
              "side walls farther than this from the hint's ray are not the entry's", 0.1, 100.0);
  s.AddDouble("ray_spacing", &o.ray_spacing, "m", "between the rays along the walls and across the face", 0.01, 2.0);
  s.AddDouble("max_square_angle", &o.max_square_angle, "rad",
              "the face's normal at most this far off the entry's axis (the cutter's cutter.max_square_angle)", 0.01,
              1.5);
  s.AddInt("min_wall_hits", &o.min_wall_hits, "rays that must hit each side wall", 2, 1000);
}

double EntryGeometry::LeftLimit(double x0, double x1) const {
  return Extreme(left_wall, 0, x0, x1, 1.0, std::min(left_fit.At(x0), left_fit.At(x1)));
}

double EntryGeometry::RightLimit(double x0, double x1) const {
  return Extreme(right_wall, 0, x0, x1, -1.0, std::max(right_fit.At(x0), right_fit.At(x1)));
}

double EntryGeometry::FaceLimit(double y0, double y1) const {
  const double x = Extreme(face_segments, 1, y0, y1, 1.0, std::numeric_limits<double>::infinity());
  return std::isfinite(x) ? x : 0.0;
}

EntryResult FindEntry(const TaskMap& map, const Eigen::Vector2d& hint, double direction, const EntryOptions& o) {
  EntryResult result;
  auto fail = [&](std::string why) {
    result.reason = std::move(why);
    return result;
  };
  if (!hint.allFinite() || !std::isfinite(direction)) return fail("the face hint is not finite");
  if (map.walls.empty()) return fail("the map has no walls");
  const std::vector<Segment> boundary = map.Boundary();
  const size_t num_walls = map.walls.size();
  const StaticSegmentIndex index(boundary);
  auto is_wall = [&](int i) { return static_cast<size_t>(i) < num_walls; };
  // A wall seen from its free side (contour maps only know which side that is).
  auto seen_from = [&](const Eigen::Vector2d& p, int i) {
    return !map.oriented || SignedDistanceToLine(p, boundary[static_cast<size_t>(i)]) > 0.0;
  };

  // The face hint: the first thing straight ahead.
  const Eigen::Vector2d u(std::cos(direction), std::sin(direction)), v(-u.y(), u.x());
  const auto ahead = index.CastRayDir(hint, u, o.max_face_distance);
  const std::string from = "ahead of " + Point(hint) + " towards " + Deg(direction);
  if (!ahead)
    return fail("the face hint points at nothing: no wall within " + FixedNumber(o.max_face_distance) + " m " + from);
  if (!is_wall(ahead->segment))
    return fail("the face hint points at unexplored space: a frontier " + FixedNumber(ahead->range) + " m " + from +
                " (no face mapped there yet)");
  if (!seen_from(hint, ahead->segment))
    return fail("the face hint is not in free space: the wall " + FixedNumber(ahead->range) + " m " + from +
                " is seen from behind");
  const Eigen::Vector2d f0 = hint + ahead->range * u;

  // The side walls, from points back along the ray (never through a wall behind the face).
  const Eigen::Vector2d behind_start = f0 - 0.01 * u;
  const auto behind = index.CastRayDir(behind_start, -u, o.wall_search_length);
  const double t_max = behind ? behind->range - 0.05 : o.wall_search_length;
  struct SideHit {
    Eigen::Vector2d local;  // (-t, offset): x along u from f0, y along v
    int segment;
  };
  std::vector<SideHit> sides[2];  // 0 left, 1 right
  int rays = 0;
  for (double t = o.ray_spacing; t <= t_max; t += o.ray_spacing) {
    ++rays;
    const Eigen::Vector2d p = f0 - t * u;
    for (int side = 0; side < 2; ++side) {
      const double sign = side == 0 ? 1.0 : -1.0;
      const auto h = index.CastRayDir(p, sign * v, o.max_half_width);
      if (!h || !is_wall(h->segment) || !seen_from(p, h->segment)) continue;
      if (AngleTo(boundary[static_cast<size_t>(h->segment)], u) > kWallAngle) continue;
      sides[side].push_back({Eigen::Vector2d(-t, sign * h->range), h->segment});
    }
  }
  const char* side_name[2] = {"left", "right"};
  const std::string where = "within " + FixedNumber(o.max_half_width) + " m of the " +
                            FixedNumber(std::max(0.0, std::min(t_max, o.wall_search_length))) +
                            " m before the face at " + Point(f0);
  if (sides[0].size() < static_cast<size_t>(o.min_wall_hits) && sides[1].size() < static_cast<size_t>(o.min_wall_hits))
    return fail("no entry walls found: " + std::to_string(sides[0].size()) + " left and " +
                std::to_string(sides[1].size()) + " right of " + std::to_string(rays) +
                " rays met a wall along the way " + where);
  for (int side = 0; side < 2; ++side) {
    std::vector<double> offsets;
    for (const SideHit& h : sides[side]) offsets.push_back(h.local.y());
    if (!offsets.empty()) {
      const double median = Median(offsets);
      std::erase_if(sides[side], [&](const SideHit& h) { return std::abs(h.local.y() - median) > kWallOutlier; });
    }
    if (sides[side].size() < static_cast<size_t>(o.min_wall_hits))
      return fail("no entry wall found on the " + std::string(side_name[side]) + ": " +
                  std::to_string(sides[side].size()) + " of " + std::to_string(rays) + " rays met one " + where);
  }

  // The axis: the mean direction of the two walls; the width across it.
  std::vector<Eigen::Vector2d> local[2];
  for (int side = 0; side < 2; ++side)
    for (const SideHit& h : sides[side]) local[side].push_back(h.local);
  const WallLine left0 = FitLine(local[0]), right0 = FitLine(local[1]);
  const double alpha = 0.5 * (std::atan(left0.b) + std::atan(right0.b));
  const Eigen::Vector2d axis = std::cos(alpha) * u + std::sin(alpha) * v, across(-axis.y(), axis.x());
  std::vector<double> widths;
  for (const SideHit& l : sides[0])
    for (const SideHit& r : sides[1])
      if (std::abs(l.local.x() - r.local.x()) < 1e-9) widths.push_back((l.local.y() - r.local.y()) * std::cos(alpha));
  const double width = widths.empty() ? (left0.a - right0.a) * std::cos(alpha) : Median(widths);

  // The face: rays along the axis across the entry, from far enough back that an oblique face
  // (up to max_square_angle) is still ahead of every ray.
  const double back = 0.5 * width * std::tan(o.max_square_angle) + 1.0;
  const double s_lo = right0.a * std::cos(alpha) + kFaceRayMargin, s_hi = left0.a * std::cos(alpha) - kFaceRayMargin;
  std::vector<Eigen::Vector2d> face_hits;
  std::vector<int> face_ids;
  int face_rays = 0;
  for (double s = s_lo; s <= s_hi + 1e-9; s += std::min(o.ray_spacing, kFaceRaySpacing)) {
    ++face_rays;
    const Eigen::Vector2d q = f0 - back * axis + s * across;
    const auto h = index.CastRayDir(q, axis, back + o.max_face_distance);
    if (!h || !is_wall(h->segment) || !seen_from(q, h->segment)) continue;
    if (AngleTo(boundary[static_cast<size_t>(h->segment)], across) > o.max_square_angle + kFaceAngleSlack) continue;
    face_hits.push_back(q + h->range * axis);
    face_ids.push_back(h->segment);
  }
  if (!face_hits.empty()) {
    std::vector<double> depth;
    for (const Eigen::Vector2d& p : face_hits) depth.push_back((p - f0).dot(axis));
    const double median = Median(depth);
    std::vector<Eigen::Vector2d> kept;
    std::vector<int> kept_ids;
    for (size_t k = 0; k < face_hits.size(); ++k)
      if (std::abs(depth[k] - median) <= kFaceOutlier) kept.push_back(face_hits[k]), kept_ids.push_back(face_ids[k]);
    face_hits = std::move(kept);
    face_ids = std::move(kept_ids);
  }
  if (face_hits.size() < static_cast<size_t>(kMinFaceHits))
    return fail("no face across the entry: " + std::to_string(face_hits.size()) + " of " + std::to_string(face_rays) +
                " rays along the " + FixedNumber(width) + " m entry met a face " + from);

  // Total least squares through the face hits; its normal into the coal.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : face_hits) mean += p;
  mean /= static_cast<double>(face_hits.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : face_hits) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  const Eigen::Vector2d along = eig.eigenvectors().col(1).normalized();  // the largest spread
  Eigen::Vector2d normal(-along.y(), along.x());
  if (normal.dot(axis) < 0.0) normal = -normal;
  const double heading = std::atan2(normal.y(), normal.x());
  const double face_angle = NormalizeAngle(heading - std::atan2(axis.y(), axis.x()));
  if (std::abs(face_angle) > o.max_square_angle)
    return fail("the face is " + Deg(std::abs(face_angle)) +
                " off square to the entry (the cutter squares up to at most " + Deg(o.max_square_angle) + ")");
  const Eigen::Vector2d left_dir(-normal.y(), normal.x());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& p : face_hits) {
    lo = std::min(lo, (p - mean).dot(left_dir));
    hi = std::max(hi, (p - mean).dot(left_dir));
  }

  EntryGeometry e;
  e.face = Segment(mean + lo * left_dir, mean + hi * left_dir);
  const Eigen::Vector2d middle = 0.5 * (e.face.a + e.face.b);
  e.axis = std::atan2(axis.y(), axis.x());
  e.entry_frame = Pose2(middle.x(), middle.y(), e.axis);
  e.face_frame = Pose2(middle.x(), middle.y(), heading);
  e.face_angle = face_angle;
  e.width = width;
  e.face_distance = ahead->range;
  const Pose2 to_entry = e.entry_frame.inverse(), to_face = e.face_frame.inverse();
  std::vector<Segment>* walls[2] = {&e.left_wall, &e.right_wall};
  std::vector<Eigen::Vector2d>* hits[2] = {&e.left_hits, &e.right_hits};
  for (int side = 0; side < 2; ++side) {
    std::set<int> ids;
    for (const SideHit& h : sides[side]) {
      hits[side]->push_back(to_entry * (f0 + h.local.x() * u + h.local.y() * v));
      ids.insert(h.segment);
    }
    for (const int i : ids) walls[side]->push_back(Transformed(to_entry, boundary[static_cast<size_t>(i)]));
  }
  e.left_fit = FitLine(e.left_hits);
  e.right_fit = FitLine(e.right_hits);
  for (const Eigen::Vector2d& p : face_hits) e.face_hits.push_back(to_face * p);
  for (const int i : std::set<int>(face_ids.begin(), face_ids.end()))
    e.face_segments.push_back(Transformed(to_face, boundary[static_cast<size_t>(i)]));
  result.entry = std::move(e);
  return result;
}

}  // namespace minenav
