// The Moving AI readers on small texts: what they accept, and one clear line for each kind
// of bad input.

#include "planner/movingai.h"

#include <gtest/gtest.h>

#include "common/file_io.h"

namespace minenav {
namespace {

const char* kMap = "type octile\nheight 3\nwidth 4\nmap\n.@..\n..T.\nGS.W\n";

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MovingAiMapTest, ReadsTerrainAsFreeOrBlocked) {
  const OccupancyGrid g = ParseMovingAiMap(kMap, "m.map");
  EXPECT_EQ(g.width, 4);
  EXPECT_EQ(g.height, 3);
  EXPECT_TRUE(g.Free(0, 0));
  EXPECT_FALSE(g.Free(1, 0));  // @
  EXPECT_FALSE(g.Free(2, 1));  // T
  EXPECT_TRUE(g.Free(0, 2));   // G
  EXPECT_TRUE(g.Free(1, 2));   // S
  EXPECT_FALSE(g.Free(3, 2));  // W
  // Windows line ends are fine.
  EXPECT_EQ(ParseMovingAiMap("type octile\r\nheight 1\r\nwidth 2\r\nmap\r\n.@\r\n", "w.map").width, 2);
}

TEST(MovingAiMapTest, BadMapsGiveOneLineNamingTheLine) {
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("", "m.map"); }),
            "m.map:1: not a Moving AI map: the first line must be 'type octile'");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight x\nwidth 4\nmap\n", "m.map"); }),
            "m.map:2: expected 'height N', got 'height x'");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 0\nwidth 4\nmap\n", "m.map"); }),
            "m.map:2: height 0 is not in [1, 100000]");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 2\nwidth 2\nmap\n..\n", "m.map"); }),
            "m.map:6: the map has 1 rows, the header says 2");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 1\nwidth 3\nmap\n..\n", "m.map"); }),
            "m.map:5: row has 2 cells, the header says 3");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 1\nwidth 2\nmap\n.x\n", "m.map"); }),
            "m.map:5: unknown terrain 'x' in column 1");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 1\nwidth 2\nmap\n..\n..\n", "m.map"); }),
            "m.map:6: text after the last map row");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiMap("type octile\nheight 1\nwidth 2\nmop\n..\n", "m.map"); }),
            "m.map:4: expected the line 'map'");
}

TEST(MovingAiScenarioTest, ReadsProblemsAndChecksThemAgainstTheMap) {
  const std::string text =
      "version 1\n0\tmaps/m.map\t4\t3\t0\t0\t3\t0\t3.41421\n1\tmaps/m.map\t4\t3\t0\t2\t2\t2\t2\n";
  const auto s = ParseMovingAiScenarios(text, "m.scen");
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].bucket, 0);
  EXPECT_EQ(s[0].map, "maps/m.map");
  EXPECT_EQ(s[0].goal, (GridCell{3, 0}));
  EXPECT_DOUBLE_EQ(s[0].optimal_length, 3.41421);
  EXPECT_EQ(s[1].start, (GridCell{0, 2}));
  const OccupancyGrid g = ParseMovingAiMap(kMap, "m.map");
  EXPECT_NO_THROW(CheckScenariosFitMap(s, g, "m.scen"));
  auto wrong = s;
  wrong[1].map_width = 5;
  EXPECT_EQ(ErrorOf([&] { CheckScenariosFitMap(wrong, g, "m.scen"); }),
            "m.scen: scenario 1: is for a 5 x 3 map, the map is 4 x 3");
  wrong = s;
  wrong[0].goal.y = 3;
  EXPECT_EQ(ErrorOf([&] { CheckScenariosFitMap(wrong, g, "m.scen"); }), "m.scen: scenario 0: start or goal outside the map");
}

TEST(MovingAiScenarioTest, BadScenarioFilesGiveOneLineNamingTheLine) {
  EXPECT_EQ(ErrorOf([] { ParseMovingAiScenarios("version 2\n", "s"); }),
            "s:1: not a Moving AI scenario file: the first line must be 'version 1'");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiScenarios("version 1\n0\tm\t4\t3\t0\t0\t3\n", "s"); }),
            "s:2: expected 9 tab-separated fields, got 7");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiScenarios("version 1\n0\tm\t4\t3\t-1\t0\t3\t0\t1\n", "s"); }),
            "s:2: start x '-1' is not a non-negative integer");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiScenarios("version 1\n0\tm\t4\t3\t1\t0\t3\t0\tabc\n", "s"); }),
            "s:2: optimal length 'abc' is not a number");
  EXPECT_EQ(ErrorOf([] { ParseMovingAiScenarios("version 1\n0\tm\t4\t3\t1\t0\t3\t0\tnan\n", "s"); }),
            "s:2: optimal length 'nan' is not a finite non-negative number");
}

}  // namespace
}  // namespace minenav
