#pragma once
// The map a pose estimator localises against when it arrives on the bus: LINE_MAP
// (line_map_t) and, optionally, CONTOUR_MAP (contour_map_t, every contour as its segments).
// One rule for "is this a new map?": its segments differ from the last map handed on
// (SameSegments). A re-published map costs nothing, and a mapper that restarted and counts
// its versions from 1 again is still heard.

#include <functional>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"

namespace minenav {

// A contour map as segments: consecutive points joined, closed contours closed.
std::vector<Segment> ContourMapSegments(const ContourMapMessage& map);

class MapUpdates {
 public:
  // `what` names the map in logs and errors ("LINE_MAP 'mine' version 3").
  using Handler = std::function<void(const std::vector<Segment>& segments, const std::string& what)>;

  // Subscribes to line_channel and contour_channel, each unless it is empty (the path
  // tracker follows the contour map alone). The object must
  // outlive the bus's dispatching (the subscriptions refer to it).
  MapUpdates(Bus& bus, const std::string& line_channel, const std::string& contour_channel, Handler on_new_map);
  MapUpdates(const MapUpdates&) = delete;
  MapUpdates& operator=(const MapUpdates&) = delete;

  int maps_handed_on() const { return maps_handed_on_; }

 private:
  void Offer(std::vector<Segment> segments, const std::string& what);

  Handler on_new_map_;
  std::vector<Segment> last_;
  int maps_handed_on_ = 0;
};

}  // namespace minenav
