#include "planner/search_limits.h"

#include "common/config.h"

namespace minenav {

std::string LimitReason(SearchStatus limit, int64_t expansions, int64_t states) {
  const std::string what = limit == SearchStatus::kStopped ? "stopped on request" : "stopped by " + ToString(limit);
  return what + " after " + std::to_string(expansions) + " expansions and " + std::to_string(states) + " states";
}

std::string ToString(SearchStatus status) {
  switch (status) {
    case SearchStatus::kFound: return "found";
    case SearchStatus::kNoPath: return "no_path";
    case SearchStatus::kInvalidRequest: return "invalid_request";
    case SearchStatus::kExpansionLimit: return "expansion_limit";
    case SearchStatus::kMemoryLimit: return "memory_limit";
    case SearchStatus::kStopped: return "stopped";
  }
  return "unknown";
}

SearchStatus CheckLimits(const SearchLimits& limits, int64_t expansions, int64_t states) {
  if (expansions >= limits.max_expansions) return SearchStatus::kExpansionLimit;
  if (states >= limits.max_states) return SearchStatus::kMemoryLimit;
  if (limits.stop_requested && expansions % kStopPollInterval == 0 && limits.stop_requested())
    return SearchStatus::kStopped;
  return SearchStatus::kFound;
}

void DeclareOptions(OptionScope scope, SearchLimits& limits) {
  scope.AddInt64("max_expansions", &limits.max_expansions, "nodes expanded before the search gives up", 1);
  scope.AddInt64("max_states", &limits.max_states, "states stored (memory) before the search gives up", 1);
}

}  // namespace minenav
