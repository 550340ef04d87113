#include "common/node/map_updates.h"

#include <utility>

#include "common/node/conversions.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/line_map_t.hpp"

namespace minenav {

std::vector<Segment> ContourMapSegments(const ContourMapMessage& map) {
  std::vector<Segment> out;
  for (const ContourPolyline& c : map.contours) {
    for (size_t i = 1; i < c.points.size(); ++i) out.emplace_back(c.points[i - 1], c.points[i]);
    if (c.closed && c.points.size() > 2) out.emplace_back(c.points.back(), c.points.front());
  }
  return out;
}

MapUpdates::MapUpdates(Bus& bus, const std::string& line_channel, const std::string& contour_channel,
                       Handler on_new_map)
    : on_new_map_(std::move(on_new_map)) {
  if (!line_channel.empty())
    Subscribe<line_map_t>(bus, line_channel, [this, line_channel](const line_map_t& m) {
      Offer(SegmentsFromLcm(m), line_channel + " '" + m.name + "' version " + std::to_string(m.version));
    });
  if (contour_channel.empty()) return;
  Subscribe<contour_map_t>(bus, contour_channel, [this, contour_channel](const contour_map_t& m) {
    Offer(ContourMapSegments(ContourMapFromLcm(m)), contour_channel + " version " + std::to_string(m.version));
  });
}

void MapUpdates::Offer(std::vector<Segment> segments, const std::string& what) {
  if (maps_handed_on_ > 0 && SameSegments(last_, segments)) return;
  on_new_map_(segments, what);
  last_ = std::move(segments);
  ++maps_handed_on_;
}

}  // namespace minenav
