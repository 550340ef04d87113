#pragma once
// What may stop a search before it has an answer: a budget of expansions and of stored
// states (memory), and an optional stop callback through which a node adds a deadline. The
// library itself reads no clock; every search says which bound stopped it.

#include <cstdint>
#include <functional>
#include <string>

namespace minenav {

class OptionScope;

struct SearchLimits {
  // Nodes taken off the open list before the search gives up. Default 2,000,000.
  int64_t max_expansions = 2'000'000;
  // States stored (open and closed) before the search gives up: about 40 bytes each in the
  // grid search, 73 to 78 in the SE(2) search (Se2PlanResult::memory_bytes). Default 8,000,000.
  int64_t max_states = 8'000'000;
  // Asked every kStopPollInterval expansions; true stops the search (a node's deadline, a
  // signal). Empty = never.
  std::function<bool()> stop_requested;
};

inline constexpr int64_t kStopPollInterval = 256;

// Why a search ended.
enum class SearchStatus {
  kFound,            // a path
  kNoPath,           // the whole reachable space was searched: the goal is not in it
  kInvalidRequest,   // start or goal outside the map, in collision, NaN, empty map, ...
  kExpansionLimit,   // SearchLimits::max_expansions
  kMemoryLimit,      // SearchLimits::max_states
  kStopped,          // SearchLimits::stop_requested (deadline)
};

// "found", "no_path", "invalid_request", "expansion_limit", "memory_limit", "stopped".
std::string ToString(SearchStatus status);
// The one line a search gives when `limit` (a bound, or a stop request) ended it.
std::string LimitReason(SearchStatus limit, int64_t expansions, int64_t states);

// The limit that is reached after `expansions` expansions with `states` stored states, or
// kFound when none is (polls stop_requested every kStopPollInterval expansions).
SearchStatus CheckLimits(const SearchLimits& limits, int64_t expansions, int64_t states);

// max_expansions, max_states.
void DeclareOptions(OptionScope scope, SearchLimits& limits);

}  // namespace minenav
