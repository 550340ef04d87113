#include "mapper/contour_map_io.h"

#include <cmath>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/file_io.h"

namespace minenav::mapper {

std::string CheckContourGeometry(const std::vector<Eigen::Vector2d>& points, bool closed) {
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return "point " + std::to_string(i) + " is not finite";
    if (std::abs(p.x()) > kMaxMapCoordinate || std::abs(p.y()) > kMaxMapCoordinate) {
      std::ostringstream why;
      why << "point " << i << " (" << p.x() << ", " << p.y() << ") is farther than " << kMaxMapCoordinate
          << " m from the origin";
      return why.str();
    }
  }
  const size_t segments = points.size() < 2 ? 0 : (closed ? points.size() : points.size() - 1);
  for (size_t k = 0; k < segments; ++k) {
    const double length = (points[(k + 1) % points.size()] - points[k]).norm();
    if (length > kMaxSegmentLength) {
      std::ostringstream why;
      why << "segment " << k << " is " << length << " m long, more than the " << kMaxSegmentLength
          << " m a contour segment may be";
      return why.str();
    }
  }
  return "";
}

ContourMap ParseContourMapJson(const std::string& text, const std::string& source, double grid_cell_size) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    std::string what = e.what();
    if (const auto nl = what.find('\n'); nl != std::string::npos) what = what.substr(0, nl);
    throw InputError(source + ": not valid JSON (" + what + ")");
  }
  if (!j.is_object() || !j.contains("contours") || !j["contours"].is_array())
    throw InputError(source + ": expected an object with a \"contours\" array");
  ContourMap map(grid_cell_size);
  const auto& contours = j["contours"];
  for (size_t k = 0; k < contours.size(); ++k) {
    const auto& c = contours[k];
    const std::string where = source + ": contour " + std::to_string(k);
    if (!c.is_object()) throw InputError(where + ": expected an object");
    bool closed = false;
    if (c.contains("closed")) {
      if (!c["closed"].is_boolean()) throw InputError(where + ": \"closed\" must be true or false");
      closed = c["closed"].get<bool>();
    }
    if (!c.contains("points") || !c["points"].is_array()) throw InputError(where + ": missing \"points\" array");
    std::vector<Eigen::Vector2d> points;
    for (size_t i = 0; i < c["points"].size(); ++i) {
      const auto& p = c["points"][i];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw InputError(where + ": point " + std::to_string(i) + " must be [x, y] numbers");
      const double x = p[0].get<double>(), y = p[1].get<double>();
      if (!std::isfinite(x) || !std::isfinite(y))
        throw InputError(where + ": point " + std::to_string(i) + " is not finite");
      points.emplace_back(x, y);
    }
    if (points.size() < (closed ? 3u : 2u))
      throw InputError(where + ": " + std::to_string(points.size()) + " points, need at least " +
                       (closed ? "3 for a closed contour" : "2"));
    if (const std::string why = CheckContourGeometry(points, closed); !why.empty()) throw InputError(where + ": " + why);
    map.Create(std::move(points), closed);
  }
  return map;
}

ContourMap LoadContourMapJson(const std::string& path, double grid_cell_size) {
  return ParseContourMapJson(ReadFile(path), path, grid_cell_size);
}

std::string ContourMapToJson(const ContourMap& map) {
  std::ostringstream os;
  os << std::setprecision(9);  // sub-micrometre for maps up to kilometres
  os << "{\"contours\": [";
  bool first = true;
  for (const auto& [id, c] : map.contours()) {
    os << (first ? "\n" : ",\n") << "  {\"id\": " << id << ", \"closed\": " << (c.closed ? "true" : "false")
       << ", \"points\": [";
    for (size_t i = 0; i < c.points.size(); ++i)
      os << (i ? ", " : "") << "[" << c.points[i].x() << ", " << c.points[i].y() << "]";
    os << "]}";
    first = false;
  }
  os << (first ? "" : "\n") << "]}\n";
  return os.str();
}

void SaveContourMapJson(const std::string& path, const ContourMap& map) {
  WriteFileAtomically(path, ContourMapToJson(map));
}

}  // namespace minenav::mapper
