#pragma once
// CPU time of the calling thread, for the compute_time nodes report (a node may read
// clocks; algorithm libraries may not).

#include <ctime>

namespace minenav {

inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace minenav
