#include "planner/contour_map_contours.h"

#include <utility>

namespace minenav {

std::vector<mapper::Contour> ContoursOf(ContourMapMessage map) {
  std::vector<mapper::Contour> contours;
  contours.reserve(map.contours.size());
  for (ContourPolyline& c : map.contours) {
    mapper::Contour contour;
    contour.id = static_cast<int>(c.id);
    contour.closed = c.closed;
    contour.points = std::move(c.points);
    contours.push_back(std::move(contour));
  }
  return contours;
}

}  // namespace minenav
