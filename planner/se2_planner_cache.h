#pragma once
// Planners kept for the maps and options they were built for. Building an Se2Planner (the
// walls' index, the clearance field, the centre cells) costs more than most searches on it,
// and a node asks for the same few planners on one map version again and again: the path
// planner for each request and replan, the task planner for the survey's paths, its roomy
// stations and the advance's maneuvers. A kept planner also keeps what its searches learned
// (the 2-D heuristic of recent goals, the swept primitives).
//
// A planner is the same when its map (segment for segment), footprint (vertex for vertex)
// and options (every field) are; the least recently used goes when `capacity` are kept.
// Planners are handed out shared: one evicted while a caller holds it stays valid for that
// caller. Not thread-safe (like the planners themselves): one cache per worker thread.

#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <vector>

#include "common/geometry.h"
#include "planner/footprint.h"
#include "planner/se2_planner.h"

namespace minenav {

class Se2PlannerCache {
 public:
  explicit Se2PlannerCache(size_t capacity = 8) : capacity_(capacity < 1 ? 1 : capacity) {}

  // The planner for (map, footprint, options): the kept one when there is one, else a new
  // one (a setup error is kept too: the same map fails the same way).
  std::shared_ptr<const Se2Planner> Get(const std::vector<Segment>& map, const Footprint& footprint,
                                        const Se2PlannerOptions& options);
  // Forget every planner (a new map version: none of them will be asked for again).
  void Clear() { kept_.clear(); }

  size_t size() const { return kept_.size(); }
  // Planners built since construction (tests, logs: a cache hit builds none).
  int64_t built() const { return built_; }

 private:
  struct Kept {
    Footprint footprint;  // as asked (the planner keeps it normalised)
    std::shared_ptr<const Se2Planner> planner;
  };
  size_t capacity_;
  std::list<Kept> kept_;  // most recently used first
  int64_t built_ = 0;
};

// The planner from `cache` when there is one, else built for this caller alone.
std::shared_ptr<const Se2Planner> PlannerFor(Se2PlannerCache* cache, const std::vector<Segment>& map,
                                             const Footprint& footprint, const Se2PlannerOptions& options);

}  // namespace minenav
