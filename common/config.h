#pragma once
// Parameters for every process: documented defaults, a config file, command-line
// overrides, --help and --print-config. A module declares its options once:
//
//   ConfigSchema schema("vehicle_sim", "Skid-steer miner simulator.");
//   schema.AddDouble("max_speed", &options.max_speed, "m/s", "Forward speed limit", 0.0, 5.0);
//   if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
//
// Libraries declare their options structs through an OptionScope (below) beside the struct;
// a process nests them (`pose.final_threshold`), so every field is reachable by name.
//
// Precedence: defaults < --config FILE (key = value lines, # comments) < --key=value
// (or --key value). Unknown keys, bad values and out-of-range values throw UsageError
// with a one-line message naming the file and line, or the flag. Exit code 2 for those.

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace minenav {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ParseOutcome { kRun, kExit };

// LCM's longest channel name (LCM_MAX_CHANNEL_NAME_LENGTH in 1.3.1).
inline constexpr size_t kMaxChannelNameLength = 63;
// Throws UsageError unless `channel` is a channel name or pattern LCM accepts (a POSIX
// extended regular expression of at most kMaxChannelNameLength characters). In 1.3.1 an
// invalid pattern makes LCM hand back a subscription whose next use crashes.
void ValidateChannelPattern(const std::string& channel);

inline constexpr int kExitUsage = 2;    // bad flag, config or input file
inline constexpr int kExitRuntime = 3;  // failure while running
// Stopped by SIGINT/SIGTERM before the work was done (a batch run before the end of its
// log): what was done is kept under names that say partial (FILE.partial).
inline constexpr int kExitInterrupted = 130;

class ConfigSchema {
 public:
  ConfigSchema(std::string program, std::string summary);

  void AddDouble(const std::string& key, double* value, const std::string& unit,
                 const std::string& help, double min = -std::numeric_limits<double>::infinity(),
                 double max = std::numeric_limits<double>::infinity());
  void AddInt(const std::string& key, int* value, const std::string& help,
              int min = std::numeric_limits<int>::min(), int max = std::numeric_limits<int>::max());
  void AddInt64(const std::string& key, int64_t* value, const std::string& help,
                int64_t min = std::numeric_limits<int64_t>::min(),
                int64_t max = std::numeric_limits<int64_t>::max());
  void AddBool(const std::string& key, bool* value, const std::string& help);
  // `choices` empty = any string.
  void AddString(const std::string& key, std::string* value, const std::string& help,
                 std::vector<std::string> choices = {});
  // A string option that names an LCM channel; --help lists these apart, with direction
  // ("subscribes" / "publishes") and the message type.
  void AddChannel(const std::string& key, std::string* value, const std::string& direction,
                  const std::string& type, const std::string& help);
  // A number kept in something other than a double (a duration in integer microseconds):
  // `get` and `set` convert. Parsed, range-checked and printed like AddDouble.
  void AddNumber(const std::string& key, const std::string& unit, const std::string& help, double min, double max,
                 std::function<double()> get, std::function<void(double)> set);
  // One of `choices` (an enum): `get` names the current value, `set(i)` takes choices[i].
  void AddChoice(const std::string& key, const std::string& help, std::vector<std::string> choices,
                 std::function<std::string()> get, std::function<void(size_t)> set);

  // Free-form text appended to --help (examples, exit codes).
  void AddHelpEpilog(const std::string& text) { epilog_ += text; }
  // Positional arguments: name shown in usage; min/max count.
  void SetPositional(const std::string& usage, size_t min_count, size_t max_count);

  // Handles --help, --print-config, --config FILE and --key=value. Returns kExit after
  // printing help or config. Throws UsageError on anything wrong.
  ParseOutcome Parse(int argc, const char* const* argv);
  ParseOutcome Parse(const std::vector<std::string>& args);  // args without argv[0]

  // Another name for `key` (an older or shorter flag): accepted on the command line and in
  // files, listed in --help beside the key; --print-config prints the key only.
  void AddAlias(const std::string& alias, const std::string& key);

  void LoadFile(const std::string& path);             // key = value lines
  // The same from text: `source` names it in errors ("preset carmen").
  void LoadText(const std::string& text, const std::string& source);
  void Set(const std::string& key, const std::string& text, const std::string& where);

  // True when `key` was given in a config file or on the command line (not its default).
  bool WasSet(const std::string& key) const { return set_keys_.count(key) > 0; }

  std::string HelpText() const;
  std::string ConfigText() const;  // the effective configuration in file syntax
  // Every option as a Markdown table (key, unit, default, meaning): what module READMEs
  // show, printed by --print-options-table.
  std::string OptionsTable() const;
  const std::vector<std::string>& positional() const { return positional_; }
  const std::string& program() const { return program_; }

  // What was declared, in declaration order (tests that every option is reachable; tools).
  struct OptionInfo {
    std::string key;
    std::string kind;  // number, integer, bool, string, channel
    std::string unit;
    std::vector<std::string> choices;  // empty = any value of the kind
  };
  std::vector<OptionInfo> Options() const;

 private:
  struct Entry {
    std::string key, unit, help, kind, default_text;
    std::vector<std::string> choices;
    std::string channel_direction, channel_type;  // for channels only
    std::function<void(const std::string& text, const std::string& where)> set;
    std::function<std::string()> get;
  };
  Entry* Find(const std::string& key);
  const Entry* Find(const std::string& key) const;
  void Add(Entry entry);

  std::string program_, summary_, epilog_;
  std::vector<Entry> entries_;
  std::string positional_usage_;
  size_t positional_min_ = 0, positional_max_ = 0;
  std::vector<std::string> positional_;
  std::set<std::string> set_keys_;
  std::map<std::string, std::string> aliases_;  // alias -> key
};

// Options under one key prefix. A library declares its options struct through a scope
// beside the struct (`void DeclareOptions(OptionScope scope, MatchOptions& o)`), and the
// process places it: DeclareOptions(OptionScope(schema).Nested("pose"), options.pose)
// makes `pose.final_threshold` (flag --pose.final-threshold). A scope is a small value.
class OptionScope {
 public:
  explicit OptionScope(ConfigSchema& schema, std::string prefix = "")
      : schema_(&schema), prefix_(std::move(prefix)) {}

  OptionScope Nested(const std::string& name) const { return OptionScope(*schema_, Key(name)); }
  std::string Key(const std::string& name) const { return prefix_.empty() ? name : prefix_ + "." + name; }
  ConfigSchema& schema() const { return *schema_; }

  void AddDouble(const std::string& name, double* value, const std::string& unit, const std::string& help,
                 double min = -std::numeric_limits<double>::infinity(),
                 double max = std::numeric_limits<double>::infinity()) const {
    schema_->AddDouble(Key(name), value, unit, help, min, max);
  }
  void AddInt(const std::string& name, int* value, const std::string& help,
              int min = std::numeric_limits<int>::min(), int max = std::numeric_limits<int>::max()) const {
    schema_->AddInt(Key(name), value, help, min, max);
  }
  void AddInt64(const std::string& name, int64_t* value, const std::string& help,
                int64_t min = std::numeric_limits<int64_t>::min(),
                int64_t max = std::numeric_limits<int64_t>::max()) const {
    schema_->AddInt64(Key(name), value, help, min, max);
  }
  void AddBool(const std::string& name, bool* value, const std::string& help) const {
    schema_->AddBool(Key(name), value, help);
  }
  void AddString(const std::string& name, std::string* value, const std::string& help,
                 std::vector<std::string> choices = {}) const {
    schema_->AddString(Key(name), value, help, std::move(choices));
  }
  // An enum, named by ToString(value) (found beside the enum): `values` are the choices.
  template <typename Enum>
  void AddEnum(const std::string& name, Enum* value, const std::string& help, const std::vector<Enum>& values) const {
    std::vector<std::string> names;
    for (const Enum v : values) names.emplace_back(ToString(v));
    schema_->AddChoice(
        Key(name), help, std::move(names), [value] { return std::string(ToString(*value)); },
        [value, values](size_t i) { *value = values[i]; });
  }
  // A duration given in seconds and kept in integer microseconds (what clocks count).
  void AddMicroseconds(const std::string& name, int64_t* value_us, const std::string& help, double min_s,
                       double max_s) const;
  // `alias` is a whole key (not prefixed): the flat name a process has always accepted.
  void AddAlias(const std::string& alias, const std::string& name) const { schema_->AddAlias(alias, Key(name)); }
  // Each of `names` also as the root key `flat_prefix + name`: the flat flags a process took
  // before its options nested (Nested("match").AddFlatAliases({"min_threshold"})).
  void AddFlatAliases(const std::vector<std::string>& names, const std::string& flat_prefix = "") const {
    for (const std::string& name : names) AddAlias(flat_prefix + name, name);
  }

 private:
  ConfigSchema* schema_;
  std::string prefix_;
};

// The value option `key` will have once Parse() runs, read before the options are declared
// (a preset that picks the defaults of the others): --key VALUE / --key=VALUE on the command
// line, else `key = value` in the --config file, else nullopt. Throws UsageError when the
// config file cannot be read.
std::optional<std::string> PeekOption(const std::vector<std::string>& args, const std::string& key);
std::optional<std::string> PeekOption(int argc, const char* const* argv, const std::string& key);

// Parses "0.33", "3.33deg" or "0.1rad" into radians when `angle` is true; plain doubles
// otherwise. Throws UsageError naming `what`.
double ParseNumber(const std::string& text, const std::string& what, bool angle = false);
// "a,b,c" -> numbers; entries may carry "deg" when angle_mask says so.
std::vector<double> ParseNumberList(const std::string& text, const std::string& what,
                                    size_t expected_count);

}  // namespace minenav
