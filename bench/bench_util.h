#pragma once
// Small helpers shared by the benchmarks (bench/*.cc): thread CPU time,
// medians, a printed table and a JSON report (--json-out FILE).

#include <algorithm>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/config.h"

namespace minenav::bench {

// CPU seconds of the calling thread: the machine is shared, and "on one core here" is what
// the targets ask for, so wall-clock time would measure the neighbours.
inline double Now() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

inline double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double Max(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

inline double Rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

// Parses --json-out FILE and --quick; anything else is a usage error (exit 2).
struct BenchArgs {
  std::string json_out;
  bool quick = false;
};
inline BenchArgs ParseBenchArgs(int argc, char** argv, const char* usage) {
  BenchArgs args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json-out" && i + 1 < argc) {
      args.json_out = argv[++i];
    } else if (a.rfind("--json-out=", 0) == 0) {
      args.json_out = a.substr(11);
    } else if (a == "--quick") {
      args.quick = true;
    } else if (a == "--help" || a == "-h") {
      std::cout << usage << "\n";
      std::exit(0);
    } else {
      std::cerr << argv[0] << ": unknown argument '" << a << "'\n" << usage << "\n";
      std::exit(2);
    }
  }
  return args;
}

inline void WriteJson(const std::string& path, const nlohmann::json& j) {
  if (path.empty()) return;
  std::ofstream out(path);
  if (!out) {
    std::cerr << "cannot write " << path << "\n";
    std::exit(3);
  }
  out << j.dump(2) << "\n";
}

// main() of a benchmark: runs `run`, turning a bad flag into one line and exit 2, any other
// failure into one line and exit 3 (the project's exit codes, common/config.h).
template <typename Run>
int RunBenchMain(const char* name, Run run, int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << "\n";
    return kExitRuntime;
  }
}

inline const char* Verdict(bool met) { return met ? "MET" : "MISSED"; }

}  // namespace minenav::bench
