#include "common/config.h"

#include <regex.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <utility>

#include "common/angle.h"

namespace minenav {

namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string FormatDouble(double v) {
  std::ostringstream os;
  os << std::setprecision(10) << v;
  return os.str();
}

template <typename T>
T ParseInteger(const std::string& text, const std::string& where, T min, T max) {
  size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    throw UsageError(where + ": '" + text + "' is not an integer");
  }
  if (used != text.size()) throw UsageError(where + ": '" + text + "' is not an integer");
  if (v < static_cast<long long>(min) || v > static_cast<long long>(max))
    throw UsageError(where + ": " + text + " is outside [" + std::to_string(min) + ", " +
                     std::to_string(max) + "]");
  return static_cast<T>(v);
}

}  // namespace

double ParseNumber(const std::string& raw, const std::string& what, bool angle) {
  std::string text = Trim(raw);
  double scale = 1.0;
  auto ends_with = [&](const std::string& suffix) {
    return text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (angle && ends_with("deg")) {
    scale = kPi / 180.0;
    text.resize(text.size() - 3);
  } else if (angle && ends_with("rad")) {
    text.resize(text.size() - 3);
  }
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    throw UsageError(what + ": '" + raw + "' is not a number");
  }
  if (used != text.size() || !std::isfinite(v)) throw UsageError(what + ": '" + raw + "' is not a finite number");
  return v * scale;
}

std::vector<double> ParseNumberList(const std::string& text, const std::string& what, size_t expected_count) {
  std::vector<double> out;
  std::istringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(ParseNumber(item, what, /*angle=*/true));
  if (expected_count && out.size() != expected_count)
    throw UsageError(what + ": '" + text + "' has " + std::to_string(out.size()) + " values, expected " +
                     std::to_string(expected_count));
  return out;
}

ConfigSchema::ConfigSchema(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary)) {}

void ConfigSchema::Add(Entry entry) {
  if (Find(entry.key)) throw std::logic_error("option '" + entry.key + "' declared twice");
  if (entry.key.empty() || entry.key.front() == '.' || entry.key.back() == '.' ||
      entry.key.find("..") != std::string::npos)
    throw std::logic_error("option key '" + entry.key + "' is not a dotted name");
  entry.default_text = entry.get();
  entries_.push_back(std::move(entry));
}

ConfigSchema::Entry* ConfigSchema::Find(const std::string& key) {
  return const_cast<Entry*>(std::as_const(*this).Find(key));
}

const ConfigSchema::Entry* ConfigSchema::Find(const std::string& key) const {
  const auto alias = aliases_.find(key);
  const std::string& name = alias == aliases_.end() ? key : alias->second;
  for (const auto& e : entries_)
    if (e.key == name) return &e;
  return nullptr;
}

void ConfigSchema::AddAlias(const std::string& alias, const std::string& key) {
  if (!Find(key)) throw std::logic_error("alias '" + alias + "' names no option '" + key + "'");
  if (Find(alias)) throw std::logic_error("alias '" + alias + "' is already an option");
  aliases_[alias] = key;
}

void ConfigSchema::AddDouble(const std::string& key, double* value, const std::string& unit,
                             const std::string& help, double min, double max) {
  AddNumber(key, unit, help, min, max, [value] { return *value; }, [value](double v) { *value = v; });
}

void ConfigSchema::AddNumber(const std::string& key, const std::string& unit, const std::string& help, double min,
                             double max, std::function<double()> get, std::function<void(double)> set) {
  Entry e;
  e.key = key;
  e.unit = unit;
  e.help = help;
  e.kind = "number";
  const bool angle = unit == "rad";
  e.set = [set, min, max, angle, key](const std::string& text, const std::string& where) {
    const double v = ParseNumber(text, where + ": " + key, angle);
    if (v < min || v > max)
      throw UsageError(where + ": " + key + " = " + text + " is outside [" + FormatDouble(min) + ", " +
                       FormatDouble(max) + "]");
    set(v);
  };
  e.get = [get] { return FormatDouble(get()); };
  Add(std::move(e));
}

void ConfigSchema::AddChoice(const std::string& key, const std::string& help, std::vector<std::string> choices,
                             std::function<std::string()> get, std::function<void(size_t)> set) {
  Entry e;
  e.key = key;
  e.help = help;
  e.kind = "string";
  for (size_t i = 0; i < choices.size(); ++i) e.unit += (i ? "|" : "") + choices[i];
  e.choices = choices;
  e.set = [set, choices, key](const std::string& raw, const std::string& where) {
    const std::string text = Trim(raw);
    const auto it = std::find(choices.begin(), choices.end(), text);
    if (it == choices.end()) {
      std::string list;
      for (size_t i = 0; i < choices.size(); ++i) list += (i ? ", " : "") + choices[i];
      throw UsageError(where + ": " + key + " = '" + text + "' is not one of " + list);
    }
    set(static_cast<size_t>(it - choices.begin()));
  };
  e.get = std::move(get);
  Add(std::move(e));
}

void OptionScope::AddMicroseconds(const std::string& name, int64_t* value_us, const std::string& help, double min_s,
                                  double max_s) const {
  schema_->AddNumber(
      Key(name), "s", help, min_s, max_s, [value_us] { return static_cast<double>(*value_us) * 1e-6; },
      [value_us](double seconds) { *value_us = std::llround(seconds * 1e6); });
}

void ConfigSchema::AddInt(const std::string& key, int* value, const std::string& help, int min, int max) {
  Entry e;
  e.key = key;
  e.help = help;
  e.kind = "integer";
  e.set = [value, min, max, key](const std::string& text, const std::string& where) {
    *value = ParseInteger<int>(Trim(text), where + ": " + key, min, max);
  };
  e.get = [value] { return std::to_string(*value); };
  Add(std::move(e));
}

void ConfigSchema::AddInt64(const std::string& key, int64_t* value, const std::string& help, int64_t min,
                            int64_t max) {
  Entry e;
  e.key = key;
  e.help = help;
  e.kind = "integer";
  e.set = [value, min, max, key](const std::string& text, const std::string& where) {
    *value = ParseInteger<int64_t>(Trim(text), where + ": " + key, min, max);
  };
  e.get = [value] { return std::to_string(*value); };
  Add(std::move(e));
}

void ConfigSchema::AddBool(const std::string& key, bool* value, const std::string& help) {
  Entry e;
  e.key = key;
  e.help = help;
  e.kind = "bool";
  e.set = [value, key](const std::string& raw, const std::string& where) {
    const std::string text = Trim(raw);
    if (text == "true" || text == "1" || text == "yes" || text == "on") *value = true;
    else if (text == "false" || text == "0" || text == "no" || text == "off") *value = false;
    else throw UsageError(where + ": " + key + " = '" + raw + "' is not true or false");
  };
  e.get = [value] { return std::string(*value ? "true" : "false"); };
  Add(std::move(e));
}

void ConfigSchema::AddString(const std::string& key, std::string* value, const std::string& help,
                             std::vector<std::string> choices) {
  if (!choices.empty()) {
    AddChoice(
        key, help, choices, [value] { return *value; },
        [value, choices](size_t i) { *value = choices[i]; });
    return;
  }
  Entry e;
  e.key = key;
  e.help = help;
  e.kind = "string";
  e.set = [value](const std::string& raw, const std::string&) { *value = Trim(raw); };
  e.get = [value] { return *value; };
  Add(std::move(e));
}

void ConfigSchema::AddChannel(const std::string& key, std::string* value, const std::string& direction,
                              const std::string& type, const std::string& help) {
  AddString(key, value, help);
  Entry& e = entries_.back();
  e.kind = "channel";
  e.channel_direction = direction;
  e.channel_type = type;
  auto inner = e.set;
  e.set = [inner, key](const std::string& text, const std::string& where) {
    if (Trim(text).empty()) throw UsageError(where + ": " + key + " must name a channel");
    try {
      ValidateChannelPattern(Trim(text));
    } catch (const UsageError& error) {
      throw UsageError(where + ": " + key + ": " + error.what());
    }
    inner(text, where);
  };
}

void ValidateChannelPattern(const std::string& channel) {
  if (channel.empty()) throw UsageError("channel name is empty");
  if (channel.size() > kMaxChannelNameLength)
    throw UsageError("channel '" + channel.substr(0, 80) + "' is longer than LCM's " +
                     std::to_string(kMaxChannelNameLength) + " characters");
  // LCM compiles "^pattern$" as a POSIX extended expression; so do we.
  regex_t compiled;
  const std::string anchored = "^" + channel + "$";
  if (regcomp(&compiled, anchored.c_str(), REG_NOSUB | REG_EXTENDED) != 0)
    throw UsageError("channel pattern '" + channel + "' is not a valid regular expression");
  regfree(&compiled);
}

void ConfigSchema::SetPositional(const std::string& usage, size_t min_count, size_t max_count) {
  positional_usage_ = usage;
  positional_min_ = min_count;
  positional_max_ = max_count;
}

void ConfigSchema::Set(const std::string& key, const std::string& text, const std::string& where) {
  Entry* e = Find(key);
  if (!e) throw UsageError(where + ": unknown option '" + key + "' (see --help)");
  e->set(text, where);
  set_keys_.insert(e->key);
}

void ConfigSchema::LoadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError(path + ": cannot open config file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw UsageError(path + ": cannot read config file");
  LoadText(text.str(), path);
}

void ConfigSchema::LoadText(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string where = source + ":" + std::to_string(line_no);
    const auto hash = line.find('#');
    const std::string content = Trim(hash == std::string::npos ? line : line.substr(0, hash));
    if (content.empty()) continue;
    const auto eq = content.find('=');
    if (eq == std::string::npos) throw UsageError(where + ": expected 'key = value', got '" + content + "'");
    Set(Trim(content.substr(0, eq)), Trim(content.substr(eq + 1)), where);
  }
}

ParseOutcome ConfigSchema::Parse(int argc, const char* const* argv) {
  std::vector<std::string> args;
  for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
  return Parse(args);
}

ParseOutcome ConfigSchema::Parse(const std::vector<std::string>& args) {
  bool help = false, print_config = false, print_table = false;
  // Config files first, wherever they appear, so that flags override them.
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--help" || args[i] == "-h") help = true;
    if (args[i] == "--config") {
      if (i + 1 >= args.size()) throw UsageError("--config needs a file name");
      LoadFile(args[++i]);
    } else if (args[i].rfind("--config=", 0) == 0) {
      LoadFile(args[i].substr(9));
    }
  }
  if (help) {
    std::fputs(HelpText().c_str(), stdout);
    return ParseOutcome::kExit;
  }
  positional_.clear();
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--config") {
      ++i;
      continue;
    }
    if (a.rfind("--config=", 0) == 0) continue;
    if (a == "--print-config") {
      print_config = true;
      continue;
    }
    if (a == "--print-options-table") {
      print_table = true;
      continue;
    }
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string key = a.substr(2), value;
    const auto eq = key.find('=');
    if (eq != std::string::npos) {
      value = key.substr(eq + 1);
      key = key.substr(0, eq);
    } else {
      std::replace(key.begin(), key.end(), '-', '_');
      Entry* e = Find(key);
      if (!e) throw UsageError("unknown option --" + a.substr(2) + " (see --help)");
      if (e->kind == "bool" && (i + 1 >= args.size() || args[i + 1].rfind("--", 0) == 0)) {
        value = "true";  // bare --flag
      } else {
        if (i + 1 >= args.size()) throw UsageError("--" + a.substr(2) + " needs a value");
        value = args[++i];
      }
    }
    std::replace(key.begin(), key.end(), '-', '_');
    Set(key, value, "--" + key);
  }
  if (positional_.size() < positional_min_ || positional_.size() > positional_max_) {
    if (positional_max_ == 0) throw UsageError("unexpected argument '" + positional_.front() + "' (see --help)");
    throw UsageError("expected " + positional_usage_ + " (see --help)");
  }
  if (print_table) {
    std::fputs(OptionsTable().c_str(), stdout);
    return ParseOutcome::kExit;
  }
  if (print_config) {
    std::fputs(ConfigText().c_str(), stdout);
    return ParseOutcome::kExit;
  }
  return ParseOutcome::kRun;
}

std::string ConfigSchema::HelpText() const {
  std::ostringstream os;
  os << "Usage: " << program_ << " [--config FILE] [--key=value ...]"
     << (positional_usage_.empty() ? "" : " " + positional_usage_) << "\n\n"
     << summary_ << "\n";
  auto print = [&](bool channels) {
    for (const auto& e : entries_) {
      if ((e.kind == "channel") != channels) continue;
      std::string flag = "--" + e.key;
      std::replace(flag.begin(), flag.end(), '_', '-');
      os << "  " << std::left << std::setw(26) << flag << " ";
      for (const auto& [alias, key] : aliases_) {
        if (key != e.key) continue;
        std::string alias_flag = "--" + alias;
        std::replace(alias_flag.begin(), alias_flag.end(), '_', '-');
        os << "(also " << alias_flag << ") ";
      }
      if (channels) {
        os << e.channel_direction << " " << e.channel_type << " on '" << e.default_text << "'. " << e.help << "\n";
      } else {
        os << e.help;
        if (!e.unit.empty()) os << " [" << e.unit << "]";
        os << " (default: " << (e.default_text.empty() ? "\"\"" : e.default_text) << ")\n";
      }
    }
  };
  bool any_channel = std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.kind == "channel"; });
  if (any_channel) {
    os << "\nChannels:\n";
    print(true);
  }
  os << "\nOptions (also as 'key = value' lines in a --config file; flags override the file):\n";
  print(false);
  os << "  " << std::left << std::setw(26) << "--config FILE" << " read options from FILE first\n"
     << "  " << std::setw(26) << "--print-config" << " print the effective configuration and exit\n"
     << "  " << std::setw(26) << "--print-options-table" << " print the options as a Markdown table and exit\n"
     << "  " << std::setw(26) << "--help" << " this text\n";
  if (!epilog_.empty()) os << "\n" << epilog_ << (epilog_.back() == '\n' ? "" : "\n");
  return os.str();
}

std::string ConfigSchema::ConfigText() const {
  std::ostringstream os;
  os << "# " << program_ << " configuration\n";
  for (const auto& e : entries_) {
    // Every line of a help that spans lines is a comment: the text must read back with
    // --config (the config fuzz target found a multi-line help that did not, issue 16).
    std::istringstream help(e.help + (e.unit.empty() ? "" : " [" + e.unit + "]"));
    for (std::string line; std::getline(help, line);) os << "# " << line << "\n";
    os << e.key << " = " << e.get() << "\n";
  }
  return os.str();
}

std::vector<ConfigSchema::OptionInfo> ConfigSchema::Options() const {
  std::vector<OptionInfo> out;
  for (const Entry& e : entries_) out.push_back({e.key, e.kind, e.unit, e.choices});
  return out;
}

std::string ConfigSchema::OptionsTable() const {
  auto cell = [](std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    std::string out;
    for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
  };
  std::ostringstream os;
  os << "| key | unit | default | meaning |\n|---|---|---|---|\n";
  for (const auto& e : entries_) {
    const std::string unit = e.kind == "channel" ? e.channel_direction + " " + e.channel_type : e.unit;
    os << "| `" << e.key << "` | " << cell(unit) << " | `" << cell(e.default_text.empty() ? "\"\"" : e.default_text)
       << "` | " << cell(e.help) << " |\n";
  }
  return os.str();
}

std::optional<std::string> PeekOption(const std::vector<std::string>& args, const std::string& key) {
  std::string flag = "--" + key;
  std::replace(flag.begin(), flag.end(), '_', '-');
  const std::string flag_underscores = "--" + key;
  std::optional<std::string> from_command_line, config_file;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    for (const std::string& f : {flag, flag_underscores}) {
      if (a == f && i + 1 < args.size()) from_command_line = args[i + 1];
      if (a.rfind(f + "=", 0) == 0) from_command_line = a.substr(f.size() + 1);
    }
    if (a == "--config" && i + 1 < args.size()) config_file = args[i + 1];
    if (a.rfind("--config=", 0) == 0) config_file = a.substr(9);
  }
  if (from_command_line) return Trim(*from_command_line);
  if (!config_file) return std::nullopt;
  std::ifstream in(*config_file);
  if (!in) throw UsageError(*config_file + ": cannot open config file");
  std::optional<std::string> value;
  std::string line;
  while (std::getline(in, line)) {
    const auto hash = line.find('#');
    const std::string content = Trim(hash == std::string::npos ? line : line.substr(0, hash));
    const auto eq = content.find('=');
    if (eq != std::string::npos && Trim(content.substr(0, eq)) == key) value = Trim(content.substr(eq + 1));
  }
  return value;
}

std::optional<std::string> PeekOption(int argc, const char* const* argv, const std::string& key) {
  return PeekOption(std::vector<std::string>(argv + (argc > 0 ? 1 : 0), argv + argc), key);
}

}  // namespace minenav
