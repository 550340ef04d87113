#include "planner/movingai.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "common/file_io.h"

namespace minenav {
namespace {

[[noreturn]] void Fail(const std::string& source, int line, const std::string& what) {
  throw InputError(source + ":" + std::to_string(line) + ": " + what);
}

// Lines without their '\r' (files written on Windows).
std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

bool ParseInt(const std::string& s, int& out) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, out);
  return r.ec == std::errc() && r.ptr == end && !s.empty();
}

int HeaderValue(const std::vector<std::string>& lines, size_t i, const std::string& key, const std::string& source) {
  const int line = static_cast<int>(i) + 1;
  if (i >= lines.size()) Fail(source, line, "missing header line '" + key + " N'");
  std::istringstream in(lines[i]);
  std::string k, v, extra;
  in >> k >> v;
  int n = 0;
  if (k != key || !ParseInt(v, n) || (in >> extra))
    Fail(source, line, "expected '" + key + " N', got '" + lines[i] + "'");
  if (n < 1 || n > 100000) Fail(source, line, key + " " + v + " is not in [1, 100000]");
  return n;
}

}  // namespace

OccupancyGrid ParseMovingAiMap(const std::string& text, const std::string& source) {
  const std::vector<std::string> lines = SplitLines(text);
  if (lines.empty() || lines[0].rfind("type ", 0) != 0)
    Fail(source, 1, "not a Moving AI map: the first line must be 'type octile'");
  const int height = HeaderValue(lines, 1, "height", source);
  const int width = HeaderValue(lines, 2, "width", source);
  if (static_cast<int64_t>(width) * height > 100'000'000)
    Fail(source, 3, "map of " + std::to_string(width) + " x " + std::to_string(height) + " cells is too large");
  if (lines.size() < 4 || lines[3] != "map") Fail(source, 4, "expected the line 'map'");
  if (lines.size() < 4 + static_cast<size_t>(height))
    Fail(source, static_cast<int>(lines.size()) + 1,
         "the map has " + std::to_string(lines.size() - 4) + " rows, the header says " + std::to_string(height));
  OccupancyGrid grid(width, height);
  for (int y = 0; y < height; ++y) {
    const std::string& row = lines[4 + static_cast<size_t>(y)];
    const int line = 5 + y;
    if (static_cast<int>(row.size()) != width)
      Fail(source, line, "row has " + std::to_string(row.size()) + " cells, the header says " + std::to_string(width));
    for (int x = 0; x < width; ++x) {
      const char c = row[static_cast<size_t>(x)];
      if (c == '.' || c == 'G' || c == 'S') continue;
      if (c == '@' || c == 'O' || c == 'T' || c == 'W') {
        grid.SetBlocked(x, y, true);
        continue;
      }
      Fail(source, line, std::string("unknown terrain '") + c + "' in column " + std::to_string(x));
    }
  }
  for (size_t i = 4 + static_cast<size_t>(height); i < lines.size(); ++i)
    if (!lines[i].empty()) Fail(source, static_cast<int>(i) + 1, "text after the last map row");
  return grid;
}

OccupancyGrid LoadMovingAiMap(const std::string& path) { return ParseMovingAiMap(ReadFile(path), path); }

std::vector<MovingAiScenario> ParseMovingAiScenarios(const std::string& text, const std::string& source) {
  const std::vector<std::string> lines = SplitLines(text);
  if (lines.empty() || (lines[0] != "version 1" && lines[0] != "version 1.0"))
    Fail(source, 1, "not a Moving AI scenario file: the first line must be 'version 1'");
  std::vector<MovingAiScenario> scenarios;
  for (size_t i = 1; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    if (lines[i].empty()) continue;
    std::vector<std::string> f;
    std::istringstream in(lines[i]);
    for (std::string field; std::getline(in, field, '\t');) f.push_back(field);
    if (f.size() != 9) Fail(source, line, "expected 9 tab-separated fields, got " + std::to_string(f.size()));
    MovingAiScenario s;
    s.map = f[1];
    int* ints[7] = {&s.bucket, &s.map_width, &s.map_height, &s.start.x, &s.start.y, &s.goal.x, &s.goal.y};
    const size_t columns[7] = {0, 2, 3, 4, 5, 6, 7};
    const char* names[7] = {"bucket", "width", "height", "start x", "start y", "goal x", "goal y"};
    for (int k = 0; k < 7; ++k)
      if (!ParseInt(f[columns[k]], *ints[k]) || *ints[k] < 0)
        Fail(source, line, std::string(names[k]) + " '" + f[columns[k]] + "' is not a non-negative integer");
    try {
      size_t used = 0;
      s.optimal_length = std::stod(f[8], &used);
      if (used != f[8].size()) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      Fail(source, line, "optimal length '" + f[8] + "' is not a number");
    }
    if (!std::isfinite(s.optimal_length) || s.optimal_length < 0.0)
      Fail(source, line, "optimal length '" + f[8] + "' is not a finite non-negative number");
    scenarios.push_back(std::move(s));
  }
  return scenarios;
}

std::vector<MovingAiScenario> LoadMovingAiScenarios(const std::string& path) {
  return ParseMovingAiScenarios(ReadFile(path), path);
}

void CheckScenariosFitMap(const std::vector<MovingAiScenario>& scenarios, const OccupancyGrid& grid,
                          const std::string& source) {
  for (size_t i = 0; i < scenarios.size(); ++i) {
    const MovingAiScenario& s = scenarios[i];
    const std::string where = source + ": scenario " + std::to_string(i) + ": ";
    if (s.map_width != grid.width || s.map_height != grid.height)
      throw InputError(where + "is for a " + std::to_string(s.map_width) + " x " + std::to_string(s.map_height) +
                       " map, the map is " + std::to_string(grid.width) + " x " + std::to_string(grid.height));
    if (!grid.Contains(s.start.x, s.start.y) || !grid.Contains(s.goal.x, s.goal.y))
      throw InputError(where + "start or goal outside the map");
  }
}

}  // namespace minenav
