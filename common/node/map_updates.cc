#include "common/node/map_updates.h"

#include <exception>
#include <utility>

#include "common/log.h"
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

void MapUpdates::SetRateBound(const Clock& clock, int64_t min_interval_us) {
  clock_ = &clock;
  min_interval_us_ = min_interval_us;
}

bool MapUpdates::Due() const {
  if (clock_ == nullptr || min_interval_us_ <= 0 || !last_attempt_us_) return true;
  const int64_t now = clock_->NowUtime();
  return now < *last_attempt_us_ || now - *last_attempt_us_ >= min_interval_us_;  // a clock set back: due
}

void MapUpdates::HandOn(std::vector<Segment> segments, const std::string& what) {
  waiting_.reset();
  if (clock_ != nullptr) last_attempt_us_ = clock_->NowUtime();  // a refused map cost its work too
  on_new_map_(segments, what);
  last_ = std::move(segments);
  ++maps_handed_on_;
}

void MapUpdates::Offer(std::vector<Segment> segments, const std::string& what) {
  if (maps_handed_on_ > 0 && SameSegments(last_, segments)) {
    waiting_.reset();  // the map in use is the latest again
    return;
  }
  if (waiting_ && SameSegments(waiting_->segments, segments)) return;
  if (!Due()) {
    waiting_ = Waiting{std::move(segments), what};
    return;
  }
  HandOn(std::move(segments), what);
}

bool MapUpdates::HandOnDue() {
  if (!waiting_ || !Due()) return false;
  Waiting w = std::move(*waiting_);
  try {
    HandOn(std::move(w.segments), w.what);
  } catch (const std::exception& e) {
    MINENAV_LOG(kWarn) << w.what << " refused: " << e.what();
    return false;
  }
  return true;
}

}  // namespace minenav
