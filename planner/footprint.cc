#include "planner/footprint.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/file_io.h"
#include "common/geometry.h"

namespace minenav {
namespace {

double SignedArea(const std::vector<Eigen::Vector2d>& v) {
  double a = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& p = v[i];
    const Eigen::Vector2d& q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

Segment Edge(const std::vector<Eigen::Vector2d>& v, size_t i) { return {v[i], v[(i + 1) % v.size()]}; }

}  // namespace

Footprint Footprint::Rectangle(double width, double length) {
  const double hw = 0.5 * width, hl = 0.5 * length;
  return {{{hl, hw}, {-hl, hw}, {-hl, -hw}, {hl, -hw}}};
}

std::string ValidateFootprint(const Footprint& f) {
  const auto& v = f.vertices;
  if (v.size() < 3) return "footprint needs at least 3 vertices, has " + std::to_string(v.size());
  for (const auto& p : v)
    if (!p.allFinite()) return "footprint has a non-finite vertex";
  for (size_t i = 0; i < v.size(); ++i)
    for (size_t j = i + 2; j < v.size(); ++j) {
      if (i == 0 && j + 1 == v.size()) continue;  // neighbours through the closing edge
      if (SegmentIntersection(Edge(v, i), Edge(v, j))) return "footprint edges cross (not a simple polygon)";
    }
  if (std::abs(SignedArea(v)) < 1e-9) return "footprint has no area";
  if (!PolygonContains(v, Eigen::Vector2d::Zero()))
    return "footprint does not contain the vehicle's origin (the pose the planner plans for)";
  return "";
}

Footprint Normalized(Footprint f) {
  if (SignedArea(f.vertices) < 0.0) std::reverse(f.vertices.begin(), f.vertices.end());
  return f;
}

double InscribedRadius(const Footprint& f) {
  double r = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < f.vertices.size(); ++i)
    r = std::min(r, PointToSegmentDistance(Eigen::Vector2d::Zero(), Edge(f.vertices, i)));
  return PolygonContains(f.vertices, Eigen::Vector2d::Zero()) ? r : 0.0;
}

double CircumscribedRadius(const Footprint& f) {
  double r = 0.0;
  for (const auto& p : f.vertices) r = std::max(r, p.norm());
  return r;
}

bool PolygonContains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if (PointToSegmentDistance(p, {a, b}) == 0.0) return true;  // on the boundary
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

Footprint ParseFootprintJson(const std::string& text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source + ": not JSON: " + std::string(e.what()).substr(0, 120));
  }
  if (!j.is_object() || !j.contains("footprint") || !j["footprint"].is_array())
    throw InputError(source + ": expected {\"footprint\": [[x, y], ...]}");
  Footprint f;
  for (const auto& p : j["footprint"]) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      throw InputError(source + ": footprint vertex " + std::to_string(f.vertices.size()) + " is not [x, y]");
    f.vertices.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  const std::string problem = ValidateFootprint(f);
  if (!problem.empty()) throw InputError(source + ": " + problem);
  return Normalized(f);
}

}  // namespace minenav
