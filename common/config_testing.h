#pragma once
// For the tests of options structs (issue 12): every field a library declares is reachable
// by its key, from a config file as from the command line, and lands in the struct.
//
//   TEST(IconicOptions, EveryKeyReachable) {
//     const auto keys = ExpectEveryOptionReachable<IconicMatchOptions>();
//     EXPECT_EQ(keys.size(), 11u);  // IconicMatchOptions has 11 fields, all declared
//   }
//
// For each key in turn: a value the schema accepts and that differs from the current one is
// set with LoadText (what a --config file does); --print-config must then show it, and so
// must a second schema declared over a copy of the struct (so the key writes the struct's own
// field, not some other variable). A field added to a struct without a declaration shows up
// as a wrong count beside the struct's test.
//
// Header-only and for tests only (it includes GoogleTest).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "common/config.h"

namespace minenav {

// The value `key` has in a --print-config text ("" when the key is missing).
inline std::string ValueInConfigText(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line;
  const std::string prefix = key + " = ";
  while (std::getline(in, line))
    if (line.rfind(prefix, 0) == 0) return line.substr(prefix.size());
  return "";
}

// Values to try for an option currently at `current`, most natural first.
inline std::vector<std::string> CandidateOptionValues(const ConfigSchema::OptionInfo& option,
                                                      const std::string& current) {
  std::vector<std::string> out;
  if (!option.choices.empty()) {
    for (const std::string& c : option.choices)
      if (c != current) out.push_back(c);
  } else if (option.kind == "bool") {
    out.push_back(current == "true" ? "false" : "true");
  } else if (option.kind == "number" || option.kind == "integer") {
    const double c = current.empty() ? 0.0 : std::stod(current);
    for (double v : {c + 1.0, c * 2.0, c / 2.0, c - 1.0, c * 1.1, c * 0.9, 1.0, 0.5, 0.0, 2.0}) {
      if (option.kind == "integer") v = std::round(v);
      std::ostringstream os;
      os.precision(10);
      os << v;
      out.push_back(os.str());
    }
  } else {
    out.push_back(current == "REACHABILITY_TEST" ? "REACHABILITY_TEST_2" : "REACHABILITY_TEST");
  }
  return out;
}

// Checks every key `declare` puts into a schema over `initial` (see the top of the file).
// Returns the keys in declaration order.
template <typename T>
std::vector<std::string> ExpectEveryOptionReachable(const T& initial,
                                                    const std::function<void(ConfigSchema&, T&)>& declare) {
  T object = initial;
  ConfigSchema schema("reachability_test", "every key reachable");
  declare(schema, object);
  std::vector<std::string> keys;
  for (const ConfigSchema::OptionInfo& option : schema.Options()) {
    keys.push_back(option.key);
    const std::string before = ValueInConfigText(schema.ConfigText(), option.key);
    bool changed = false;
    for (const std::string& value : CandidateOptionValues(option, before)) {
      try {
        schema.LoadText(option.key + " = " + value, "reachability test");
      } catch (const UsageError&) {
        continue;  // out of range: try the next one
      }
      if (ValueInConfigText(schema.ConfigText(), option.key) != before) {
        changed = true;
        break;
      }
    }
    EXPECT_TRUE(changed) << option.key << ": no accepted value changed --print-config (was " << before << ")";
    const std::string after = ValueInConfigText(schema.ConfigText(), option.key);
    T copy = object;
    ConfigSchema over_copy("reachability_test", "the copy");
    declare(over_copy, copy);
    EXPECT_EQ(ValueInConfigText(over_copy.ConfigText(), option.key), after)
        << option.key << " does not write the struct's own field";
  }
  return keys;
}

// The same for a library struct declared by DeclareOptions(OptionScope, T&), at the root.
template <typename T>
std::vector<std::string> ExpectEveryOptionReachable(const T& initial = T{}) {
  return ExpectEveryOptionReachable<T>(initial, [](ConfigSchema& s, T& o) { DeclareOptions(OptionScope(s), o); });
}

// The flat flags a process kept as aliases of nested keys (issue 12): each pair is a flag
// without its dashes and the `key = value` line --print-config must then show.
using FlagAndConfigLine = std::pair<std::string, std::string>;

// The command line that gives every flag the value of its line.
inline std::vector<std::string> FlagArgs(const std::vector<FlagAndConfigLine>& flags) {
  std::vector<std::string> args;
  for (const auto& [flag, line] : flags) {
    args.push_back("--" + flag);
    args.push_back(line.substr(line.find(" = ") + 3));
  }
  return args;
}

// The same, then --print-config: what a process test runs.
inline std::vector<std::string> PrintConfigArgs(const std::vector<FlagAndConfigLine>& flags) {
  std::vector<std::string> args = FlagArgs(flags);
  args.push_back("--print-config");
  return args;
}

// Every flag's line is in `config_text` (a --print-config output or ConfigText()).
inline void ExpectConfigLines(const std::string& config_text, const std::vector<FlagAndConfigLine>& flags) {
  for (const auto& [flag, line] : flags)
    EXPECT_NE(("\n" + config_text).find("\n" + line + "\n"), std::string::npos) << "--" << flag << ": " << line;
}

}  // namespace minenav
