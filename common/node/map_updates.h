#pragma once
// The map a pose estimator localises against when it arrives on the bus: LINE_MAP
// (line_map_t) and, optionally, CONTOUR_MAP (contour_map_t, every contour as its segments).
// One rule for "is this a new map?": its segments differ from the last map handed on
// (SameSegments). A re-published map costs nothing, and a mapper that restarted and counts
// its versions from 1 again is still heard.
//
// A rate bound (SetRateBound) for a node whose handler rebuilds expensive state (the iconic
// estimator's lookup table): a new map is handed on at most once per interval of the node's
// clock; one arriving sooner waits, the latest replacing an earlier one, until HandOnDue() is
// called after the interval (the node calls it where it needs the map, before a scan). A
// stream of a changed map per message (a hostile sender, or a mapper publishing per scan)
// then costs one rebuild per interval, not one per message.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/clock.h"
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

  // At most one map handed on per `min_interval_us` of `clock` (which must outlive this);
  // the first map is handed on when it arrives.
  void SetRateBound(const Clock& clock, int64_t min_interval_us);
  // Hands on the waiting map if there is one and the interval since the last hand-on has
  // passed. A map the handler refuses (it throws) is logged as a warning and dropped; the last
  // good map stands. Returns whether a map was handed on.
  bool HandOnDue();

  int maps_handed_on() const { return maps_handed_on_; }
  bool map_waiting() const { return waiting_.has_value(); }

 private:
  void Offer(std::vector<Segment> segments, const std::string& what);
  bool Due() const;
  void HandOn(std::vector<Segment> segments, const std::string& what);

  Handler on_new_map_;
  std::vector<Segment> last_;
  int maps_handed_on_ = 0;
  // Rate bound.
  const Clock* clock_ = nullptr;
  int64_t min_interval_us_ = 0;
  std::optional<int64_t> last_attempt_us_;  // when the handler was last called
  struct Waiting {
    std::vector<Segment> segments;
    std::string what;
  };
  std::optional<Waiting> waiting_;
};

}  // namespace minenav
