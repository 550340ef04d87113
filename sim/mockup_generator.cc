#include "sim/mockup_generator.h"

#include <cmath>
#include <Eigen/Geometry>
#include <random>

#include "common/angle.h"

namespace minenav {

namespace {

using Vec = Eigen::Vector2d;

// Table 1 (thesis 2.2): surveyed x, y (m) and gyro heading (deg); the first heading is
// "n/a" in the table and taken as 180 deg.
constexpr double kTable1[16][3] = {
    {9.822, 3.646, 180.0},    {8.248, 3.353, 187.587},  {6.685, 3.158, 181.628},  {5.088, 3.099, 177.675},
    {3.736, 3.921, 143.068},  {3.579, 5.483, 89.324},   {3.641, 7.082, 81.704},   {3.579, 8.694, 87.090},
    {3.452, 10.261, 88.179},  {3.393, 11.854, 87.090},  {3.327, 13.425, 86.689},  {4.300, 14.660, 45.035},
    {5.763, 15.258, 15.241},  {7.236, 15.793, 12.834},  {8.707, 16.392, 18.163},  {9.179, 16.517, 10.714}};

// Corridor outline (m): a U, 6 m wide, centrelines y = 3.3 (west-bound leg), x = 3.5
// (north-bound leg), y = 15.8 (east-bound leg); legs run to x = 20.
constexpr double kWestWall = 0.5, kSouthWall = 0.3, kEnd = 20.0;
constexpr double kInnerWest = 6.5, kInnerSouth = 6.3, kInnerNorth = 12.8, kNorthWall = 18.8;
constexpr double kColumn = 0.4;  // m, concrete columns jutting out of the walls

std::vector<Vec> CorridorOutline() {
  return {Vec(kWestWall, kSouthWall), Vec(kEnd, kSouthWall),      Vec(kEnd, kInnerSouth),
          Vec(kInnerWest, kInnerSouth), Vec(kInnerWest, kInnerNorth), Vec(kEnd, kInnerNorth),
          Vec(kEnd, kNorthWall),        Vec(kWestWall, kNorthWall)};
}

bool Inside(const Vec& p, const std::vector<Vec>& poly) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec& a = poly[j];
    const Vec& b = poly[i];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      inside = !inside;
  }
  return inside;
}

// A wall from `from` to `to` along an axis, with square columns jutting `kColumn` into the
// corridor (to the left of from -> to) centred at the given distances along the wall.
void WallWithColumns(const Vec& from, const Vec& to, const std::vector<double>& at, std::vector<Segment>* out) {
  const Vec dir = (to - from).normalized();
  const Vec left(-dir.y(), dir.x());
  Vec cursor = from;
  for (double s : at) {
    const Vec c0 = from + (s - 0.5 * kColumn) * dir, c1 = from + (s + 0.5 * kColumn) * dir;
    out->emplace_back(cursor, c0);
    out->emplace_back(c0, c0 + kColumn * left);
    out->emplace_back(c0 + kColumn * left, c1 + kColumn * left);
    out->emplace_back(c1 + kColumn * left, c1);
    cursor = c1;
  }
  out->emplace_back(cursor, to);
}

std::vector<Vec> Box(const Vec& center, double w, double h, double angle) {
  const Eigen::Rotation2Dd r(angle);
  std::vector<Vec> out;
  for (const Vec& c : {Vec(-w / 2, -h / 2), Vec(w / 2, -h / 2), Vec(w / 2, h / 2), Vec(-w / 2, h / 2)})
    out.push_back(center + r * c);
  return out;
}

std::vector<Vec> Octagon(const Vec& center, double diameter) {
  std::vector<Vec> out;
  for (int k = 0; k < 8; ++k) {
    const double a = k * kPi / 4.0 + kPi / 8.0;
    out.push_back(center + 0.5 * diameter * Vec(std::cos(a), std::sin(a)));
  }
  return out;
}

}  // namespace

std::vector<Segment> MockupWorld::World() const {
  std::vector<Segment> all = map;
  all.insert(all.end(), clutter.begin(), clutter.end());
  return all;
}

MockupWorld GenerateIndoorMockup(uint64_t seed) {
  MockupWorld w;
  // Concrete walls (west and south) with columns; partitions elsewhere. One closed loop.
  WallWithColumns(Vec(kWestWall, kNorthWall), Vec(kWestWall, kSouthWall), {2.3, 8.3, 14.3}, &w.map);  // west, going south
  WallWithColumns(Vec(kWestWall, kSouthWall), Vec(kEnd, kSouthWall), {6.0, 12.0, 18.0}, &w.map);    // south, going east
  const std::vector<Vec> outline = CorridorOutline();
  // Partitions from the south-east corner round to the north-west corner, where the west
  // wall starts: the corridor is one closed loop.
  for (size_t i = 1; i + 1 < outline.size(); ++i) w.map.emplace_back(outline[i], outline[i + 1]);

  for (const auto& row : kTable1) {
    Station st;
    st.pose = Pose2(row[0], row[1], NormalizeAngle(DegToRad(row[2])));
    w.stations.push_back(st);
  }

  // Clutter: people, machines, equipment, placed in the corridor away from the path.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(kWestWall, kEnd), uy(kSouthWall, kNorthWall), u01(0.0, 1.0);
  std::vector<Segment> path;
  for (size_t i = 1; i < w.stations.size(); ++i)
    path.emplace_back(w.stations[i - 1].pose.translation(), w.stations[i].pose.translation());
  std::vector<std::vector<Vec>> placed;
  const int wanted = 12;
  for (int attempt = 0; attempt < 2000 && static_cast<int>(placed.size()) < wanted; ++attempt) {
    const Vec c(ux(rng), uy(rng));
    const double kind = u01(rng);
    std::vector<Vec> shape;
    if (kind < 0.4)
      shape = Octagon(c, 0.5);  // a person
    else if (kind < 0.7)
      shape = Box(c, 1.0 + 1.5 * u01(rng), 0.8 + 0.7 * u01(rng), kPi * u01(rng));  // a machine
    else
      shape = Box(c, 0.4 + 0.6 * u01(rng), 0.4 + 0.6 * u01(rng), kPi * u01(rng));  // equipment
    bool ok = true;
    for (const Vec& v : shape) {
      ok = ok && Inside(v, outline);
      for (const Segment& s : w.map) ok = ok && PointToSegmentDistance(v, s) > 0.15;
      for (const Segment& s : path) ok = ok && PointToSegmentDistance(v, s) > 1.0;
      for (const auto& other : placed) ok = ok && (v - other.front()).norm() > 0.0 && !Inside(v, other);
    }
    for (const auto& other : placed)
      for (const Vec& v : other) ok = ok && !Inside(v, shape);
    // Edges must not cross walls (the U's inner corner) or other objects.
    for (size_t i = 0; ok && i < shape.size(); ++i) {
      const Segment e(shape[i], shape[(i + 1) % shape.size()]);
      for (const Segment& s : w.map) ok = ok && !SegmentIntersection(e, s);
      for (const Segment& s : w.clutter) ok = ok && !SegmentIntersection(e, s);
    }
    if (!ok) continue;
    placed.push_back(shape);
    for (size_t i = 0; i < shape.size(); ++i) w.clutter.emplace_back(shape[i], shape[(i + 1) % shape.size()]);
  }
  return w;
}

}  // namespace minenav
