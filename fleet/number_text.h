#pragma once
// Numbers as the fleet's messages, tables and unit files print them.

#include <sstream>
#include <string>

namespace minenav {

// `v` with exactly `decimals` decimals ("0.5" -> "0.50" for 2): table columns, countdowns.
inline std::string FixedText(double v, int decimals) {
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(decimals);
  os << v;
  return os.str();
}

// `v` in its shortest form ("0.5", "60", "1e-05"): values as the user gave them.
inline std::string NumberText(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace minenav
