#include "fleet/fleet_file.h"

#include <algorithm>
#include <cctype>
#include <functional>
#include <set>
#include <sstream>

#include "common/config.h"
#include "common/file_io.h"

namespace minenav {

namespace {

constexpr const char* kProcessKeys =
    "command, group, restart, after, ready, ready_timeout, heartbeat, required, ends_fleet, stdout, env.NAME";

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

bool IsVariableName(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// Process and group names become file and unit names: letters, digits, '_' and '-'.
bool IsProcessName(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

struct KeyValue {
  std::string key, value;
  int line = 0;
};

struct Section {
  std::string kind;  // "variables" or "process"
  std::string name;  // the process's name
  int line = 0;
  std::vector<KeyValue> entries;
};

// Variables in force and the names the file used (an override nobody uses is a typo).
class Variables {
 public:
  explicit Variables(std::map<std::string, std::string> values) : values_(std::move(values)) {}

  void Define(const std::string& name, std::string value) { values_[name] = std::move(value); }
  bool Defined(const std::string& name) const { return values_.count(name) > 0; }
  const std::map<std::string, std::string>& values() const { return values_; }
  const std::set<std::string>& used() const { return used_; }

  const std::string& Lookup(const std::string& name, const std::string& where) {
    used_.insert(name);
    const auto it = values_.find(name);
    if (it == values_.end())
      throw InputError(where + ": ${" + name + "} is not defined (define it under [variables] or give " + name +
                       "=VALUE on the command line)");
    return it->second;
  }

  // Reads "${NAME}" or "$$" at text[i] ('$'), appends its value to `out` and returns the
  // index after it. A '$' followed by anything else is kept as it is.
  size_t ExpandAt(const std::string& text, size_t i, const std::string& where, std::string& out) {
    if (i + 1 < text.size() && text[i + 1] == '$') {
      out += '$';
      return i + 2;
    }
    if (i + 1 >= text.size() || text[i + 1] != '{') {
      out += '$';
      return i + 1;
    }
    const size_t close = text.find('}', i + 2);
    if (close == std::string::npos) throw InputError(where + ": '${' without its closing '}'");
    const std::string name = text.substr(i + 2, close - i - 2);
    if (!IsVariableName(name)) throw InputError(where + ": '${" + name + "}' is not a variable name");
    out += Lookup(name, where);
    return close + 1;
  }

  // The whole text with its variables expanded (a variable's value or an env.* value).
  std::string Expand(const std::string& text, const std::string& where) {
    std::string out;
    for (size_t i = 0; i < text.size();) {
      if (text[i] == '$') {
        i = ExpandAt(text, i, where, out);
      } else {
        out += text[i++];
      }
    }
    return out;
  }

  // Words of a command: split on blanks; '...' quotes literally, "..." quotes with
  // variables expanded; a variable's value never splits a word (like "${NAME}" in a shell).
  std::vector<std::string> SplitCommand(const std::string& text, const std::string& where) {
    std::vector<std::string> words;
    std::string word;
    bool in_word = false;
    char quote = 0;
    for (size_t i = 0; i < text.size();) {
      const char c = text[i];
      if (quote != 0) {
        if (c == quote) {
          quote = 0;
          ++i;
        } else if (c == '$' && quote == '"') {
          i = ExpandAt(text, i, where, word);
        } else {
          word += c;
          ++i;
        }
      } else if (c == ' ' || c == '\t') {
        if (in_word) words.push_back(word);
        word.clear();
        in_word = false;
        ++i;
      } else {
        in_word = true;
        if (c == '\'' || c == '"') {
          quote = c;
          ++i;
        } else if (c == '$') {
          i = ExpandAt(text, i, where, word);
        } else {
          word += c;
          ++i;
        }
      }
    }
    if (quote != 0) throw InputError(where + ": a " + std::string(1, quote) + " quote is not closed");
    if (in_word) words.push_back(word);
    return words;
  }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> used_;
};

std::string At(const std::string& source, int line, const std::string& key) {
  return source + ":" + std::to_string(line) + (key.empty() ? "" : ": " + key);
}

// The line without its comment: from a '#' at the start or after a blank, outside quotes
// (like a shell: `--title 'run #2'` keeps its '#').
std::string StripComment(const std::string& line) {
  char quote = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote != 0) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
      return line.substr(0, i);
    }
  }
  return line;
}

std::vector<Section> ReadSections(const std::string& text, const std::string& source) {
  std::vector<Section> sections;
  std::istringstream in(text);
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    const int first_line = number;
    std::string line = Trim(StripComment(raw));
    // A line ending in '\' goes on on the next one (long commands).
    while (!line.empty() && line.back() == '\\') {
      line.pop_back();
      std::string next;
      if (!std::getline(in, next)) throw InputError(At(source, first_line, "") + ": the file ends after a '\\'");
      ++number;
      line = Trim(line) + " " + Trim(StripComment(next));
    }
    if (line.empty()) continue;
    if (line[0] == '[') {
      if (line.back() != ']')
        throw InputError(At(source, first_line, "") + ": '" + line + "' is not a section header ([variables] or [process NAME])");
      std::istringstream header(line.substr(1, line.size() - 2));
      Section s;
      s.line = first_line;
      header >> s.kind >> s.name;
      std::string extra;
      header >> extra;
      if (s.kind == "variables" && s.name.empty()) {
      } else if (s.kind == "process" && IsProcessName(s.name) && extra.empty()) {
      } else if (s.kind == "process") {
        throw InputError(At(source, first_line, "") + ": '" + line +
                         "': a process name is letters, digits, '_' and '-' ([process vehicle_sim])");
      } else {
        throw InputError(At(source, first_line, "") + ": unknown section '" + line +
                         "' (expected [variables] or [process NAME])");
      }
      sections.push_back(std::move(s));
      continue;
    }
    const size_t eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(At(source, first_line, "") + ": '" + line + "' is not 'key = value'");
    KeyValue kv{Trim(line.substr(0, eq)), Trim(line.substr(eq + 1)), first_line};
    if (kv.key.empty()) throw InputError(At(source, first_line, "") + ": a value without a key");
    if (sections.empty())
      throw InputError(At(source, first_line, kv.key) + ": outside any section (start with [variables] or [process NAME])");
    for (const KeyValue& other : sections.back().entries)
      if (other.key == kv.key)
        throw InputError(At(source, first_line, kv.key) + ": given twice (first on line " + std::to_string(other.line) + ")");
    sections.back().entries.push_back(std::move(kv));
  }
  return sections;
}

bool ParseBool(const KeyValue& kv, const std::string& source) {
  const std::string& v = kv.value;
  if (v == "true" || v == "yes" || v == "on" || v == "1") return true;
  if (v == "false" || v == "no" || v == "off" || v == "0") return false;
  throw InputError(At(source, kv.line, kv.key) + ": '" + v + "' is not true or false");
}

template <typename Enum>
Enum ParseChoice(const KeyValue& kv, const std::string& source, const std::vector<Enum>& values) {
  std::string list;
  for (const Enum v : values) {
    if (kv.value == ToString(v)) return v;
    list += std::string(list.empty() ? "" : ", ") + ToString(v);
  }
  throw InputError(At(source, kv.line, kv.key) + ": '" + kv.value + "' is not one of " + list);
}

std::vector<std::string> SplitNames(const std::string& text) {
  std::string spaced = text;
  std::replace(spaced.begin(), spaced.end(), ',', ' ');
  std::istringstream in(spaced);
  std::vector<std::string> names;
  for (std::string n; in >> n;) names.push_back(n);
  return names;
}

ProcessSpec ParseProcess(const Section& section, const std::string& source, Variables& variables) {
  ProcessSpec p;
  p.name = section.name;
  p.file = source;
  p.line = section.line;
  std::string heartbeat = "<default>";
  for (const KeyValue& kv : section.entries) {
    p.key_lines[kv.key] = kv.line;
    const std::string where = At(source, kv.line, kv.key);
    if (kv.key == "command") {
      p.argv = variables.SplitCommand(kv.value, where);
      if (p.argv.empty() || p.argv[0].empty()) throw InputError(where + ": no program");
    } else if (kv.key == "group") {
      if (!IsProcessName(kv.value))
        throw InputError(where + ": '" + kv.value + "' is not a group name (letters, digits, '_', '-')");
      p.group = kv.value;
    } else if (kv.key == "restart") {
      p.restart = ParseChoice(kv, source, std::vector{RestartPolicy::kNever, RestartPolicy::kOnFailure, RestartPolicy::kAlways});
    } else if (kv.key == "after") {
      p.after = SplitNames(kv.value);
    } else if (kv.key == "ready") {
      p.ready = ParseChoice(kv, source, std::vector{Readiness::kStarted, Readiness::kHeartbeat, Readiness::kOk, Readiness::kExited});
    } else if (kv.key == "ready_timeout") {
      try {
        p.ready_timeout = ParseNumber(kv.value, where);
      } catch (const UsageError& e) {
        throw InputError(e.what());
      }
      if (!(p.ready_timeout > 0 && p.ready_timeout <= 3600))
        throw InputError(where + ": " + kv.value + " is outside (0, 3600] s");
    } else if (kv.key == "heartbeat") {
      heartbeat = kv.value;
    } else if (kv.key == "required") {
      p.required = ParseBool(kv, source);
    } else if (kv.key == "ends_fleet") {
      p.ends_fleet = ParseBool(kv, source);
    } else if (kv.key == "stdout") {
      if (kv.value != "inherit" && kv.value != "log")
        throw InputError(where + ": '" + kv.value + "' is not one of inherit, log");
      p.stdout_to_log = kv.value == "log";
    } else if (kv.key.rfind("env.", 0) == 0 && IsVariableName(kv.key.substr(4))) {
      p.env[kv.key.substr(4)] = variables.Expand(kv.value, where);
    } else {
      throw InputError(where + ": unknown key (a process has " + std::string(kProcessKeys) + ")");
    }
  }
  if (p.argv.empty()) throw InputError(p.Where() + ": [process " + p.name + "] has no command");
  if (p.group.empty()) throw InputError(p.Where() + ": [process " + p.name + "] has no group (vehicle, base, ...)");
  if (heartbeat == "<default>") {
    heartbeat = p.argv[0].substr(p.argv[0].find_last_of('/') + 1);
  } else if (heartbeat == "none") {
    heartbeat.clear();
  }
  const size_t colon = heartbeat.find(':');
  p.heartbeat_process = heartbeat.substr(0, colon);
  if (colon != std::string::npos) p.heartbeat_instance = heartbeat.substr(colon + 1);
  if (!p.has_heartbeat() && (p.ready == Readiness::kHeartbeat || p.ready == Readiness::kOk))
    throw InputError(p.Where("ready") + ": '" + ToString(p.ready) + "' needs a heartbeat, but heartbeat = none");
  return p;
}

// Every `after` names another process of the file, and waiting never goes round a cycle.
void CheckDependencies(const FleetSpec& fleet) {
  for (const ProcessSpec& p : fleet.processes)
    for (const std::string& d : p.after) {
      if (d == p.name) throw InputError(p.Where("after") + ": a process cannot wait for itself");
      if (fleet.Find(d) == nullptr) throw InputError(p.Where("after") + ": no process is called '" + d + "'");
    }
  // Depth-first search; `path` is the chain being followed.
  std::map<std::string, int> mark;  // 1 = on the path, 2 = done
  std::vector<std::string> path;
  std::function<void(const ProcessSpec&)> visit = [&](const ProcessSpec& p) {
    mark[p.name] = 1;
    path.push_back(p.name);
    for (const std::string& d : p.after) {
      if (mark[d] == 1) {
        std::string cycle;
        for (auto it = std::find(path.begin(), path.end(), d); it != path.end(); ++it) cycle += *it + " -> ";
        throw InputError(fleet.Find(d)->Where("after") + ": the processes wait for each other: " + cycle + d);
      }
      if (mark[d] == 0) visit(*fleet.Find(d));
    }
    path.pop_back();
    mark[p.name] = 2;
  };
  for (const ProcessSpec& p : fleet.processes)
    if (mark[p.name] == 0) visit(p);
}

bool IsSafeShellWord(const std::string& w) {
  return !w.empty() && std::all_of(w.begin(), w.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string("_./:=,+@%-").find(c) != std::string::npos;
  });
}

}  // namespace

const char* ToString(RestartPolicy policy) {
  switch (policy) {
    case RestartPolicy::kNever: return "never";
    case RestartPolicy::kOnFailure: return "on-failure";
    case RestartPolicy::kAlways: return "always";
  }
  return "?";
}

const char* ToString(Readiness readiness) {
  switch (readiness) {
    case Readiness::kStarted: return "started";
    case Readiness::kHeartbeat: return "heartbeat";
    case Readiness::kOk: return "ok";
    case Readiness::kExited: return "exited";
  }
  return "?";
}

std::string ProcessSpec::Where() const { return At(file, line, ""); }

std::string ProcessSpec::Where(const std::string& key) const {
  const auto it = key_lines.find(key);
  return At(file, it == key_lines.end() ? line : it->second, key);
}

std::vector<std::string> FleetSpec::Groups() const {
  std::vector<std::string> groups;
  for (const ProcessSpec& p : processes)
    if (std::find(groups.begin(), groups.end(), p.group) == groups.end()) groups.push_back(p.group);
  return groups;
}

const ProcessSpec* FleetSpec::Find(const std::string& name) const {
  for (const ProcessSpec& p : processes)
    if (p.name == name) return &p;
  return nullptr;
}

FleetSpec ParseFleetFile(const std::string& text, const std::string& source,
                         const std::map<std::string, std::string>& builtins,
                         const std::map<std::string, std::string>& overrides) {
  const std::vector<Section> sections = ReadSections(text, source);
  for (const auto& [name, value] : overrides)
    if (builtins.count(name) > 0)
      throw InputError(source + ": " + name + " is built in" +
                       (name == kOutVariable ? std::string(": set the output folder with --out") : std::string()));
  std::map<std::string, std::string> initial = builtins;
  initial.insert(overrides.begin(), overrides.end());
  Variables variables(initial);
  std::set<std::string> declared;  // names under [variables]

  // [variables] first, in file order (each may use the ones above it), so a process
  // section may come before the variables it uses.
  for (const Section& s : sections) {
    if (s.kind != "variables") continue;
    for (const KeyValue& kv : s.entries) {
      const std::string where = At(source, kv.line, kv.key);
      if (!IsVariableName(kv.key)) throw InputError(where + ": a variable name is letters, digits and '_'");
      if (builtins.count(kv.key) > 0) throw InputError(where + ": " + kv.key + " is built in and cannot be redefined");
      if (!declared.insert(kv.key).second) throw InputError(where + ": defined twice");
      if (overrides.count(kv.key) == 0) variables.Define(kv.key, variables.Expand(kv.value, where));
    }
  }

  FleetSpec fleet;
  fleet.source = source;
  for (const Section& s : sections) {
    if (s.kind != "process") continue;
    if (fleet.Find(s.name) != nullptr)
      throw InputError(At(source, s.line, "") + ": a second [process " + s.name + "]");
    fleet.processes.push_back(ParseProcess(s, source, variables));
  }
  if (fleet.processes.empty()) throw InputError(source + ": no [process NAME] section");
  for (const auto& [name, value] : overrides)
    if (declared.count(name) == 0 && variables.used().count(name) == 0)
      throw InputError(source + ": " + name + "=" + value + " on the command line: the file uses no variable " + name);
  CheckDependencies(fleet);
  fleet.variables = variables.values();
  return fleet;
}

FleetSpec SelectGroups(const FleetSpec& fleet, const std::vector<std::string>& groups) {
  if (groups.empty()) return fleet;
  const std::vector<std::string> known = fleet.Groups();
  for (const std::string& g : groups)
    if (std::find(known.begin(), known.end(), g) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw InputError(fleet.source + ": no process is in group '" + g + "' (its groups: " + list + ")");
    }
  FleetSpec selected = fleet;
  selected.processes.clear();
  for (const ProcessSpec& p : fleet.processes)
    if (std::find(groups.begin(), groups.end(), p.group) != groups.end()) selected.processes.push_back(p);
  for (ProcessSpec& p : selected.processes)
    std::erase_if(p.after, [&](const std::string& d) { return selected.Find(d) == nullptr; });
  return selected;
}

std::map<std::string, std::string> ParseOverrides(const std::vector<std::string>& words) {
  std::map<std::string, std::string> overrides;
  for (const std::string& w : words) {
    const size_t eq = w.find('=');
    if (eq == std::string::npos || !IsVariableName(w.substr(0, eq)))
      throw InputError("'" + w + "' is not NAME=VALUE (a variable of the fleet file)");
    overrides[w.substr(0, eq)] = w.substr(eq + 1);
  }
  return overrides;
}

std::vector<size_t> StartOrder(const FleetSpec& fleet) {
  std::vector<size_t> order;
  std::vector<bool> placed(fleet.processes.size(), false);
  // In waves, as the supervisor starts them: first all that wait for nothing, then all that
  // wait only for those, ... (file order within a wave; CheckDependencies ruled out cycles).
  while (order.size() < fleet.processes.size()) {
    std::vector<size_t> wave;
    for (size_t i = 0; i < fleet.processes.size(); ++i) {
      if (placed[i]) continue;
      const auto& after = fleet.processes[i].after;
      const bool ready = std::all_of(after.begin(), after.end(), [&](const std::string& d) {
        for (size_t j = 0; j < fleet.processes.size(); ++j)
          if (fleet.processes[j].name == d) return static_cast<bool>(placed[j]);
        return true;
      });
      if (ready) wave.push_back(i);
    }
    if (wave.empty()) break;
    for (const size_t i : wave) {
      placed[i] = true;
      order.push_back(i);
    }
  }
  return order;
}

std::string QuoteCommand(const std::vector<std::string>& argv) {
  std::string out;
  for (const std::string& w : argv) {
    if (!out.empty()) out += ' ';
    if (IsSafeShellWord(w)) {
      out += w;
      continue;
    }
    out += '\'';
    for (const char c : w) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += '\'';
  }
  return out;
}

}  // namespace minenav
