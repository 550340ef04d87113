#include "sim/changing_world.h"

#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace minenav {

namespace {

using Vec = Eigen::Vector2d;

// Closed polygon through the vertices, one segment per edge.
std::vector<Segment> Loop(const std::vector<Vec>& v) {
  std::vector<Segment> out;
  for (size_t k = 0; k < v.size(); ++k) out.emplace_back(v[k], v[(k + 1) % v.size()]);
  return out;
}

std::vector<Segment> Rect(double x0, double y0, double x1, double y1) {
  return Loop({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

void Append(std::vector<Segment>* a, const std::vector<Segment>& b) { a->insert(a->end(), b.begin(), b.end()); }

Station At(double x, double y, double theta, int world) {
  Station s;
  s.pose = Pose2(x, y, theta);
  s.world = world;
  return s;
}

// Midpoints of step-long cells along every segment: each sample stands for `step` metres.
std::vector<Vec> Samples(const std::vector<Segment>& world, double step) {
  std::vector<Vec> out;
  for (const Segment& s : world) {
    const int n = std::max(1, static_cast<int>(std::lround(s.length() / step)));
    for (int i = 0; i < n; ++i) out.push_back(s.a + ((i + 0.5) / n) * (s.b - s.a));
  }
  return out;
}

double DistanceToWorld(const Vec& p, const std::vector<Segment>& world) {
  double best = 1e300;
  for (const Segment& s : world) best = std::min(best, PointToSegmentDistance(p, s));
  return best;
}

// The sine of the angle between the ray direction and segment s.
double ViewSine(const Vec& ray, const Segment& s) {
  const Vec d = s.b - s.a;
  const double n = ray.norm() * d.norm();
  return n > 0.0 ? std::abs(ray.x() * d.y() - ray.y() * d.x()) / n : 0.0;
}

// A station of `world` sees through q (a point of a wall that is gone): the ray toward q
// passes it and hits a wall of `world` beyond it, steeply enough across q's old wall.
bool SeesThrough(const std::vector<Segment>& world, const Vec& from, const Vec& q, const Segment& old_wall,
                 double max_range, double min_view_angle) {
  const Vec ray = q - from;
  const double dist = ray.norm();
  if (dist <= 0.0 || dist > max_range) return false;
  if (ViewSine(ray, old_wall) < std::sin(min_view_angle)) return false;
  const auto hit = CastRay(from, std::atan2(ray.y(), ray.x()), world, max_range);
  return hit && hit->range > dist + 0.05;
}

// Builds the checks from the worlds and stations. `checks` holds (label, after_station).
void Judge(ChangingWorldScenario* sc, const std::vector<std::pair<std::string, int>>& checks,
           const ChangingWorldOptions& o) {
  sc->sample_step = o.sample_step;
  for (const auto& [label, after_station] : checks) {
    const int after = after_station;  // a copy: clang 14 (the fuzz build) cannot capture a structured binding
    ScenarioCheck c;
    c.label = label;
    c.after_station = after;
    c.world = sc->stations[static_cast<size_t>(after)].world;
    const std::vector<Segment>& judged = sc->worlds[static_cast<size_t>(c.world)];
    auto seen_by = [&](const Vec& p, bool only_judged_world) {
      for (int k = 0; k <= after; ++k) {
        const Station& st = sc->stations[static_cast<size_t>(k)];
        if (only_judged_world && st.world != c.world) continue;
        if (SeesWallPoint(sc->worlds[static_cast<size_t>(st.world)], st.pose.translation(), p, o.max_view_range,
                          o.min_view_angle))
          return true;
      }
      return false;
    };
    for (const Vec& p : Samples(judged, o.sample_step)) {
      if (seen_by(p, false)) c.must_stay.push_back({p, !seen_by(p, true)});
      if (seen_by(p, true)) c.must_appear.push_back({p, false});
    }
    // Walls of the other worlds, seen while they stood, gone now, and seen through.
    std::set<std::pair<long, long>> done;
    for (size_t w = 0; w < sc->worlds.size(); ++w) {
      if (static_cast<int>(w) == c.world) continue;
      for (const Segment& s : sc->worlds[w])
        for (const Vec& q : Samples({s}, o.sample_step)) {
          const std::pair<long, long> key{std::lround(q.x() * 1000.0), std::lround(q.y() * 1000.0)};
          if (done.count(key) || DistanceToWorld(q, judged) < 0.02) continue;
          bool seen = false, through = false;
          for (int k = 0; k <= after && !seen; ++k) {
            const Station& st = sc->stations[static_cast<size_t>(k)];
            seen = st.world == static_cast<int>(w) &&
                   SeesWallPoint(sc->worlds[w], st.pose.translation(), q, o.max_view_range, o.min_view_angle);
          }
          for (int k = 0; k <= after && seen && !through; ++k) {
            const Station& st = sc->stations[static_cast<size_t>(k)];
            through = st.world == c.world &&
                      SeesThrough(judged, st.pose.translation(), q, s, o.max_view_range, o.min_view_angle);
          }
          if (seen && through) {
            done.insert(key);
            c.must_go.push_back({q, false});
          }
        }
    }
    sc->checks.push_back(std::move(c));
  }
}

void Check(const ChangingWorldOptions& o) {
  if (const std::string why = ValidateOptions(o); !why.empty()) throw std::invalid_argument(why);
}

// Two rooms, A = [0, 20] x [0, 12] with two pillars, B = [20.3, 32] x [0, 12] with one,
// and a partition 0.3 m thick between them with a 2 m double doorway at y in [4.5, 6.5].
std::vector<Segment> TwoRooms() {
  std::vector<Segment> w = Rect(0, 0, 32, 12);
  Append(&w, Rect(20, 0, 20.3, 4.5));
  Append(&w, Rect(20, 6.5, 20.3, 12));
  Append(&w, Rect(5, 4, 7, 7));
  Append(&w, Rect(12, 3, 15, 5));
  Append(&w, Rect(25, 5, 27, 8));
  return w;
}

// Two leaves 5 cm thick, closed, flush with room A's face of the partition (closed loops, so
// World::SameSpace stays exact).
std::vector<Segment> DoorLeaves() {
  std::vector<Segment> w = Rect(20, 4.5, 20.05, 5.5);
  Append(&w, Rect(20, 5.5, 20.05, 6.5));
  return w;
}

}  // namespace

std::string ValidateOptions(const ChangingWorldOptions& o) {
  std::ostringstream why;
  if (!(o.sample_step > 0.0 && o.sample_step <= 1.0))
    why << "sample_step must be in (0, 1] m, got " << o.sample_step;
  else if (!(o.max_view_range > 0.0))
    why << "max_view_range must be > 0 m, got " << o.max_view_range;
  else if (!(o.min_view_angle >= 0.0 && o.min_view_angle < 1.5))
    why << "min_view_angle must be in [0, 1.5) rad, got " << o.min_view_angle;
  else if (!(o.cut_depth > 0.0 && o.cut_depth <= 5.0))
    why << "cut_depth must be in (0, 5] m, got " << o.cut_depth;
  return why.str();
}

bool SeesWallPoint(const std::vector<Segment>& world, const Vec& from, const Vec& point, double max_range,
                   double min_view_angle) {
  const Vec ray = point - from;
  const double dist = ray.norm();
  if (dist <= 1e-9 || dist > max_range) return false;
  const auto hit = CastRay(from, std::atan2(ray.y(), ray.x()), world, dist + 0.01);
  if (!hit || hit->range < dist - 1e-4) return false;
  return ViewSine(ray, world[static_cast<size_t>(hit->segment)]) >= std::sin(min_view_angle);
}

ChangingWorldScenario DoorsOpenScenario(const ChangingWorldOptions& o) {
  Check(o);
  ChangingWorldScenario sc;
  sc.name = "doors_open";
  sc.description = "Figure 23: a double door between two rooms, closed for the first scans, open for the last";
  std::vector<Segment> closed = TwoRooms();
  Append(&closed, DoorLeaves());
  sc.worlds = {closed, TwoRooms()};
  sc.stations = {At(2.5, 9.0, 0.0, 0),  At(9.5, 2.0, 0.2, 0),  At(16.0, 8.5, -0.3, 0),
                 At(17.0, 6.0, 0.1, 1), At(10.0, 8.5, 0.0, 1)};
  Judge(&sc, {{"after the doors opened", 4}}, o);
  return sc;
}

ChangingWorldScenario DoorClosedScenario(const ChangingWorldOptions& o) {
  Check(o);
  ChangingWorldScenario sc;
  sc.name = "door_closed";
  sc.description = "a double door between two rooms, open for the first scans, closed for the last";
  std::vector<Segment> closed = TwoRooms();
  Append(&closed, DoorLeaves());
  sc.worlds = {TwoRooms(), closed};
  sc.stations = {At(2.5, 9.0, 0.0, 0), At(9.5, 2.0, 0.2, 0),  At(16.0, 8.5, -0.3, 0), At(17.0, 6.0, 0.1, 0),
                 At(16.5, 5.2, 0.3, 1), At(10.0, 8.5, 0.0, 1)};
  Judge(&sc, {{"after the doors closed", 5}}, o);
  return sc;
}

ChangingWorldScenario VendingMachineScenario(const ChangingWorldOptions& o) {
  Check(o);
  ChangingWorldScenario sc;
  sc.name = "vending_machine";
  sc.description = "a trapezoidal box placed against the middle of a 24 m wall, then taken away";
  std::vector<Segment> room = Rect(0, 0, 24, 10);
  Append(&room, Rect(4, 5, 6, 7));
  Append(&room, Rect(16, 4, 19, 6));
  // 1.4 m wide at the wall, 1.0 m at the front, 0.8 m deep: three faces visible at once.
  std::vector<Segment> with_box = room;
  Append(&with_box, {Segment(11.0, 0.0, 11.2, 0.8), Segment(11.2, 0.8, 12.2, 0.8), Segment(12.2, 0.8, 12.4, 0.0)});
  sc.worlds = {room, with_box, room};
  sc.stations = {At(3.0, 2.0, 0.0, 0),  At(10.0, 3.0, 0.2, 0), At(14.0, 8.0, -0.2, 0), At(21.0, 2.0, 0.4, 0),
                 At(8.5, 3.0, 0.0, 1),  At(11.7, 5.0, 0.1, 1), At(15.0, 2.5, 0.0, 1),
                 At(9.0, 3.5, 0.0, 2),  At(14.0, 3.0, 0.0, 2)};
  Judge(&sc, {{"after the box was placed", 6}, {"after the box was taken away", 8}}, o);
  return sc;
}

ChangingWorldScenario ParkedEquipmentScenario(const ChangingWorldOptions& o) {
  Check(o);
  ChangingWorldScenario sc;
  sc.name = "parked_equipment";
  sc.description = "a 6 x 2.5 m machine parked in a room, then driven away";
  std::vector<Segment> room = Rect(0, 0, 22, 14);
  Append(&room, Rect(3, 9, 5, 11));
  Append(&room, Rect(17, 2, 19, 4));
  // The machine's footprint, centred at (11, 7), turned 20 degrees.
  const double c = std::cos(0.35), s = std::sin(0.35);
  std::vector<Vec> corners;
  for (const auto& [u, v] : std::vector<std::pair<double, double>>{{-3, -1.25}, {3, -1.25}, {3, 1.25}, {-3, 1.25}})
    corners.emplace_back(11.0 + c * u - s * v, 7.0 + s * u + c * v);
  std::vector<Segment> parked = room;
  Append(&parked, Loop(corners));
  sc.worlds = {parked, room};
  sc.stations = {At(4.0, 3.0, 0.0, 0), At(11.0, 2.5, 0.3, 0), At(18.0, 11.0, 3.0, 0), At(9.0, 12.0, -0.2, 0),
                 At(6.0, 6.5, 0.0, 1), At(8.5, 10.0, -0.5, 1), At(15.0, 7.5, 0.2, 1)};
  Judge(&sc, {{"after the machine left", 6}}, o);
  return sc;
}

ChangingWorldScenario CoalFaceScenario(const ChangingWorldOptions& o) {
  Check(o);
  ChangingWorldScenario sc;
  sc.name = "coal_face";
  sc.description = "a 6 m entry off a room; its face advanced by one cut depth";
  auto mine = [](double face_y) {
    std::vector<Segment> w =
        Loop({{0, 0}, {20, 0}, {20, 8}, {13, 8}, {13, face_y}, {7, face_y}, {7, 8}, {0, 8}});
    Append(&w, Rect(3, 3, 5, 5));
    Append(&w, Rect(15, 2, 17, 4));
    return w;
  };
  sc.worlds = {mine(18.0), mine(18.0 + o.cut_depth)};
  sc.stations = {At(10.0, 4.0, 1.57, 0), At(10.0, 10.0, 1.57, 0), At(10.0, 14.0, 1.57, 0),
                 At(10.0, 13.0, 1.57, 1), At(10.0, 15.0, 1.57, 1)};
  Judge(&sc, {{"after the face advanced", 4}}, o);
  return sc;
}

std::vector<std::string> ChangingWorldScenarioNames() {
  return {"doors_open", "door_closed", "vending_machine", "parked_equipment", "coal_face"};
}

std::vector<ChangingWorldScenario> AllChangingWorldScenarios(const ChangingWorldOptions& o) {
  return {DoorsOpenScenario(o), DoorClosedScenario(o), VendingMachineScenario(o), ParkedEquipmentScenario(o),
          CoalFaceScenario(o)};
}

ChangingWorldScenario ChangingWorldScenarioByName(const std::string& name, const ChangingWorldOptions& o) {
  if (name == "doors_open") return DoorsOpenScenario(o);
  if (name == "door_closed") return DoorClosedScenario(o);
  if (name == "vending_machine") return VendingMachineScenario(o);
  if (name == "parked_equipment") return ParkedEquipmentScenario(o);
  if (name == "coal_face") return CoalFaceScenario(o);
  std::string known;
  for (const std::string& n : ChangingWorldScenarioNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown changing-world scenario '" + name + "' (known: " + known + ")");
}

}  // namespace minenav
