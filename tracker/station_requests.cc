#include "tracker/station_requests.h"

#include <utility>

namespace minenav {

StationRequests::StationRequests(std::vector<Pose2> stations, StationRequestOptions options, int64_t first_request_id)
    : stations_(std::move(stations)), options_(options), next_id_(first_request_id) {}

std::optional<StationRequests::Request> StationRequests::Update(int64_t now) {
  if (Finished()) return std::nullopt;
  switch (phase_) {
    case Phase::kRequest: {
      if (attempts_ > 0 && static_cast<double>(now - since_) * 1e-6 < options_.retry_delay) return std::nullopt;
      Request r{next_id_++, stations_[static_cast<size_t>(station_)], station_};
      active_id_ = r.request_id;
      ++attempts_;
      phase_ = Phase::kWaitPath;
      since_ = now;
      message_ = "station " + std::to_string(station_ + 1) + "/" + std::to_string(stations_.size()) +
                 ": request " + std::to_string(r.request_id) + " (attempt " + std::to_string(attempts_) + ")";
      return r;
    }
    case Phase::kWaitPath:
      if (static_cast<double>(now - since_) * 1e-6 > options_.answer_timeout)
        Retry("no PATH for request " + std::to_string(active_id_) + " in " + std::to_string(options_.answer_timeout) +
                  " s",
              now);
      return std::nullopt;
    case Phase::kWaitDone:
      return std::nullopt;
    case Phase::kDwell:
      if (static_cast<double>(now - since_) * 1e-6 >= options_.dwell) Next(now, false);
      return std::nullopt;
  }
  return std::nullopt;
}

void StationRequests::OnPath(int64_t request_id, bool feasible, const std::string& status, int64_t now) {
  if (request_id != active_id_ || phase_ != Phase::kWaitPath) return;
  if (!feasible) {
    Retry("no path to station " + std::to_string(station_ + 1) + ": " + status, now);
    return;
  }
  phase_ = Phase::kWaitDone;
  since_ = now;
}

void StationRequests::OnStatus(int64_t task_id, int state, const std::string& message, int64_t now) {
  if (task_id != active_id_ || (phase_ != Phase::kWaitDone && phase_ != Phase::kWaitPath)) return;
  if (state == 2) {  // DONE
    phase_ = Phase::kDwell;
    since_ = now;
    message_ = "station " + std::to_string(station_ + 1) + " reached: " + message;
  } else if (state == 3 || state == 4) {  // FAILED, CANCELED
    Retry("the tracker ended request " + std::to_string(task_id) + ": " + message, now);
  }
}

void StationRequests::Retry(const std::string& why, int64_t now) {
  message_ = why;
  if (attempts_ >= options_.max_attempts) {
    message_ += "; station " + std::to_string(station_ + 1) + " skipped after " + std::to_string(attempts_) + " attempts";
    Next(now, true);
    return;
  }
  phase_ = Phase::kRequest;
  since_ = now;
}

void StationRequests::Next(int64_t now, bool skipped) {
  if (skipped) ++skipped_;
  ++station_;
  attempts_ = 0;
  phase_ = Phase::kRequest;
  active_id_ = -1;
  since_ = now;
}

}  // namespace minenav
