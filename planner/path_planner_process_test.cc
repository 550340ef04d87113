// path_planner as tools outside the project call it: the map batch contract on the crossing
// of two 6 m entries (the CSV judged by the independent checker), the exit code and one line
// when there is no path, and the grid batch contract on a small Moving AI map.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "common/file_io.h"
#include "planner/test_maps.h"
#include "planner/testing/path_checker.h"
#include "tests/child_process.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

using testing::ChildProcess;
using testing::ReadTextFile;

int RunPlanner(const std::vector<std::string>& argv, const std::string& output) {
  ChildProcess p(argv, output);
  const auto code = p.Wait(120.0);
  return code ? *code : -1;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

TEST(PathPlannerProcessTest, MapModeWritesACheckedPathCsvAndAnSvg) {
  const testing::TempDir dir("path_planner_test");
  const std::vector<Segment> map = planner_test::Crossing(6.0, 20.0);
  SaveSegmentsJson(dir / "map.json", map);
  ASSERT_EQ(RunPlanner({MINENAV_PATH_PLANNER_BIN, "--map", dir / "map.json", "--start", "0,-12,90deg", "--goal", "12,0,0",
                 "--footprint", "3.3,10", "--turn-radius", "4", "--clearance", "0", "--path-out", dir / "path.csv",
                 "--svg-out", dir / "path.svg"},
                dir / "out.txt"),
            0)
      << ReadTextFile(dir / "out.txt");
  const std::vector<std::string> rows = Lines(ReadTextFile(dir / "path.csv"));
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(rows[0], "x,y,theta,motion");
  std::vector<testing::CheckedPiece> pieces;
  Pose2 start;
  for (size_t i = 1; i < rows.size(); ++i) {
    std::istringstream in(rows[i]);
    std::string x, y, t, m;
    std::getline(in, x, ',');
    std::getline(in, y, ',');
    std::getline(in, t, ',');
    std::getline(in, m);
    const Pose2 p(std::stod(x), std::stod(y), std::stod(t));
    if (i == 1) {
      EXPECT_EQ(m, "start");
      start = p;
      continue;
    }
    Motion motion;
    ASSERT_TRUE(MotionFromString(m, motion)) << rows[i];
    pieces.push_back({static_cast<int>(motion), p});
  }
  EXPECT_NEAR(start.y, -12.0, 1e-9);
  EXPECT_NEAR(start.theta, kPi / 2, 1e-9);
  EXPECT_NEAR(pieces.back().end.x, 12.0, 1e-6);
  EXPECT_NEAR(pieces.back().end.y, 0.0, 1e-6);
  testing::PathCheckSettings st;
  st.polygon = {{5, 1.65}, {-5, 1.65}, {-5, -1.65}, {5, -1.65}};
  st.turn_radius = 4.0;
  st.pose_tolerance = 1e-6;  // the CSV's 12 digits
  const auto report = testing::CheckPath(map, start, pieces, st);
  EXPECT_TRUE(report.ok) << report.problem;
  EXPECT_GT(report.length, 16.0);
  const std::string svg = ReadTextFile(dir / "path.svg");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("footprint"), std::string::npos);
}

TEST(PathPlannerProcessTest, NoPathGivesItsExitCodeAndOneLine) {
  const testing::TempDir dir("path_planner_test");
  SaveSegmentsJson(dir / "map.json", planner_test::Crossing(6.0, 20.0));
  const std::vector<std::string> base = {MINENAV_PATH_PLANNER_BIN, "--map", dir / "map.json", "--start", "0,-12,90deg",
                                         "--path-out", dir / "path.csv"};
  auto args = base;
  args.insert(args.end(), {"--goal", "50,0,0"});
  EXPECT_EQ(RunPlanner(args, dir / "out.txt"), 4);
  const auto lines = Lines(ReadTextFile(dir / "out.txt"));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("goal (50, 0, 0) is outside the map"), std::string::npos) << lines[0];
  EXPECT_FALSE(std::filesystem::exists(dir / "path.csv"));
  args = base;
  args.insert(args.end(), {"--goal", "12,0,0", "--search.max-expansions", "3"});
  EXPECT_EQ(RunPlanner(args, dir / "out.txt"), 5);
  EXPECT_NE(ReadTextFile(dir / "out.txt").find("expansion_limit"), std::string::npos);
  args = base;
  args.insert(args.end(), {"--goal", "12,0"});
  EXPECT_EQ(RunPlanner(args, dir / "out.txt"), 2);
}

TEST(PathPlannerProcessTest, GridModeWritesOneRowPerScenario) {
  const testing::TempDir dir("path_planner_test");
  WriteFileAtomically(dir / "m.map", "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n.@.@\n");
  WriteFileAtomically(dir / "m.map.scen",
                      "version 1\n0\tm.map\t4\t3\t0\t2\t3\t1\t6\n0\tm.map\t4\t3\t0\t0\t2\t2\t0\n");
  ASSERT_EQ(RunPlanner({MINENAV_PATH_PLANNER_BIN, "--grid", dir / "m.map", "--scenarios", dir / "m.map.scen",
                 "--results-out", dir / "r.csv"},
                dir / "out.txt"),
            0)
      << ReadTextFile(dir / "out.txt");
  const auto rows = Lines(ReadTextFile(dir / "r.csv"));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "index,length,expansions,seconds");
  EXPECT_EQ(rows[1].substr(0, 4), "0,6,");  // round the walls: no diagonal past a blocked cell
  EXPECT_EQ(rows[2].substr(0, 5), "1,-1,");  // (2, 2) is walled in: no path
}

}  // namespace
}  // namespace minenav
