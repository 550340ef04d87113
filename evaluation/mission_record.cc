#include "evaluation/mission_record.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

namespace minenav {

namespace {

using nlohmann::json;

// Typed readers that name the key in their one-line error.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& where, const std::string& what) const {
    throw InputError(source_ + ": " + where + ": " + what);
  }
  double Number(const json& j, const std::string& where) const {
    if (!j.is_number()) Fail(where, "expected a number");
    const double v = j.get<double>();
    if (!std::isfinite(v)) Fail(where, "not finite");
    return v;
  }
  int Count(const json& obj, const char* key) const {
    if (!obj.contains(key)) return 0;
    const json& j = obj.at(key);
    if (!j.is_number_integer()) Fail(key, "expected an integer");
    const int64_t v = j.get<int64_t>();
    if (v < 0 || v > std::numeric_limits<int>::max()) Fail(key, "out of range");
    return static_cast<int>(v);
  }
  std::string Text(const json& obj, const char* key, const std::string& where = "") const {
    if (!obj.contains(key)) return "";
    const json& j = obj.at(key);
    if (!j.is_string()) Fail(where + key, "expected a string");
    return j.get<std::string>();
  }
  std::vector<double> Numbers(const json& j, const std::string& where) const {
    if (!j.is_array()) Fail(where, "expected an array");
    std::vector<double> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(Number(j[i], where + "[" + std::to_string(i) + "]"));
    return out;
  }

 private:
  std::string source_;
};

MissionSubtask ParseSubtask(const Reader& r, const json& t, const std::string& where) {
  if (!t.is_object()) r.Fail(where, "expected an object");
  MissionSubtask s;
  if (t.contains("id")) {
    if (!t.at("id").is_number_integer()) r.Fail(where + ".id", "expected an integer");
    s.id = t.at("id").get<int64_t>();
  }
  s.kind = r.Text(t, "kind", where + ".");
  s.description = r.Text(t, "description", where + ".");
  s.state = r.Text(t, "state", where + ".");
  if (t.contains("target")) {
    const std::vector<double> v = r.Numbers(t.at("target"), where + ".target");
    if (v.size() != 3) r.Fail(where + ".target", "expected [x, y, theta]");
    s.target = Pose2(v[0], v[1], v[2]);
  }
  if (t.contains("depth")) s.depth = r.Number(t.at("depth"), where + ".depth");
  if (t.contains("width")) s.width = r.Number(t.at("width"), where + ".width");
  if (t.contains("face")) {
    const std::vector<double> v = r.Numbers(t.at("face"), where + ".face");
    if (v.size() != 4) r.Fail(where + ".face", "expected [x1, y1, x2, y2]");
    s.face = Segment({v[0], v[1]}, {v[2], v[3]});
  }
  return s;
}

}  // namespace

MissionReport ParseMissionReportJson(const std::string& text, const std::string& source) {
  const Reader r(source);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(source + ": not JSON: " + std::string(e.what()).substr(0, 200));
  }
  if (!j.is_object()) throw InputError(source + ": expected the coordinator's report (a JSON object)");
  MissionReport m;
  m.mission_id = r.Text(j, "mission_id");
  m.state = r.Text(j, "state");
  m.message = r.Text(j, "message");
  if (j.contains("seconds")) m.seconds = r.Number(j.at("seconds"), "seconds");
  m.stations_visited = r.Count(j, "stations_visited");
  m.stations_failed = r.Count(j, "stations_failed");
  m.drives = r.Count(j, "drives");
  m.drives_planned_ahead = r.Count(j, "drives_planned_ahead");
  m.replans = r.Count(j, "replans");
  m.retries = r.Count(j, "retries");
  m.resends = r.Count(j, "resends");
  m.pauses_for_lost_processes = r.Count(j, "pauses_for_lost_processes");
  if (j.contains("planning_waits_s")) m.planning_waits_s = r.Numbers(j.at("planning_waits_s"), "planning_waits_s");
  if (j.contains("events")) {
    const json& e = j.at("events");
    if (!e.is_array()) r.Fail("events", "expected an array");
    for (size_t i = 0; i < e.size(); ++i) {
      if (!e[i].is_string()) r.Fail("events[" + std::to_string(i) + "]", "expected a string");
      m.events.push_back(e[i].get<std::string>());
    }
  }
  if (j.contains("subtasks")) {
    const json& s = j.at("subtasks");
    if (!s.is_array()) r.Fail("subtasks", "expected an array");
    for (size_t i = 0; i < s.size(); ++i) m.subtasks.push_back(ParseSubtask(r, s[i], "subtasks[" + std::to_string(i) + "]"));
  }
  return m;
}

}  // namespace minenav
