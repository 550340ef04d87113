#include "planner/se2_planner_cache.h"

namespace minenav {

std::shared_ptr<const Se2Planner> Se2PlannerCache::Get(const std::vector<Segment>& map, const Footprint& footprint,
                                                       const Se2PlannerOptions& options) {
  for (auto it = kept_.begin(); it != kept_.end(); ++it) {
    if (!(it->planner->options() == options) || it->footprint.vertices != footprint.vertices ||
        !SameSegments(it->planner->map(), map))
      continue;
    kept_.splice(kept_.begin(), kept_, it);  // most recently used first
    return kept_.front().planner;
  }
  ++built_;
  kept_.push_front({footprint, std::make_shared<const Se2Planner>(map, footprint, options)});
  if (kept_.size() > capacity_) kept_.pop_back();
  return kept_.front().planner;
}

std::shared_ptr<const Se2Planner> PlannerFor(Se2PlannerCache* cache, const std::vector<Segment>& map,
                                             const Footprint& footprint, const Se2PlannerOptions& options) {
  return cache ? cache->Get(map, footprint, options) : std::make_shared<const Se2Planner>(map, footprint, options);
}

}  // namespace minenav
