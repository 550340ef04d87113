#pragma once
// How a fuzz target reports what is wrong besides a crash: one line on stderr, then abort()
// (libFuzzer keeps the input as a crash artifact).

#include <cstdio>
#include <cstdlib>
#include <string>

namespace minenav::fuzz {

[[noreturn]] inline void Fail(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

}  // namespace minenav::fuzz
