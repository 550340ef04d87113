#pragma once
// A planner that starts late or restarts (kill -9, then its supervisor) hears requests before
// the first map: the map comes within the mapper's republish period (contour_mapper
// --map-republish-period, 2 s), and the coordinator repeats every request it has no answer to
// (resend_period). Answering "no map" at once failed a whole mission after a task planner
// restart; leaving the request for its repeat costs one repeat. FirstMapWait says which
// requests to leave: live only (a batch log has no repeats), and only within `wait` seconds
// of the start, after which "no map" is the answer it always was.

#include <cmath>
#include <cstdint>

namespace minenav {

class FirstMapWait {
 public:
  // wait: s after the start; start_utime: the runtime's clock at the start (µs).
  FirstMapWait(double wait, int64_t start_utime, bool live)
      : until_utime_(live && wait > 0 ? start_utime + std::llround(wait * 1e6) : start_utime) {}

  // Without a map at now_utime: true = leave the request unanswered for its repeat.
  bool LeaveForRepeat(int64_t now_utime) const { return now_utime < until_utime_; }

 private:
  int64_t until_utime_;
};

}  // namespace minenav
