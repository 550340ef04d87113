#pragma once
// The survey's drive on the fleet's planner and tracker (survey_client): for each scan
// station in turn, ask the path planner for a path there (PATH_REQUEST), wait for its PATH,
// then for the path tracker's TASK_STATUS DONE of that request, stand still `dwell` s for the
// ladar's scans, and go on. A request without an answer in `answer_timeout` s, a path that
// is not feasible, or a tracker's FAILED is retried from where the vehicle is, `retry_delay` s
// later (the map and the vehicle may have changed: a planner that has just refused a goal
// answers the same at once), at most `max_attempts` times per station; then the station is
// skipped (reported). Plain C++: the
// caller passes the clock and the messages' contents.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/pose2.h"

namespace minenav {

struct StationRequestOptions {
  double dwell = 0.5;            // s standing still at each station
  double answer_timeout = 30.0;  // s to wait for the PATH of a request
  int max_attempts = 3;          // requests per station before it is skipped
  double retry_delay = 2.0;      // s from a failed attempt to the next request
};

class StationRequests {
 public:
  // first_request_id: request ids count up from it (make it unique per run, e.g. the clock).
  StationRequests(std::vector<Pose2> stations, StationRequestOptions options, int64_t first_request_id);

  struct Request {
    int64_t request_id = 0;
    Pose2 goal;
    int station = 0;
  };
  // At clock time now (us): a request to send now, if one is due.
  std::optional<Request> Update(int64_t now);
  // The planner's answer to request_id.
  void OnPath(int64_t request_id, bool feasible, const std::string& status, int64_t now);
  // The tracker's status of task_id (task_status_t states: 2 DONE, 3 FAILED, 4 CANCELED).
  void OnStatus(int64_t task_id, int state, const std::string& message, int64_t now);

  bool Finished() const { return station_ >= static_cast<int>(stations_.size()); }
  int station() const { return station_; }
  int skipped() const { return skipped_; }
  // One line: what it is doing or the last thing that went wrong.
  const std::string& message() const { return message_; }

 private:
  enum class Phase { kRequest, kWaitPath, kWaitDone, kDwell };
  void Retry(const std::string& why, int64_t now);
  void Next(int64_t now, bool skipped);

  std::vector<Pose2> stations_;
  StationRequestOptions options_;
  int64_t next_id_;
  int station_ = 0;
  int attempts_ = 0;
  Phase phase_ = Phase::kRequest;
  int64_t active_id_ = -1;
  int64_t since_ = 0;  // us, when the phase began
  int skipped_ = 0;
  std::string message_;
};

}  // namespace minenav
