#include "sim/scenario.h"

#include <gtest/gtest.h>

#include "sim/mockup_generator.h"

namespace minenav {
namespace {

// The one place that builds the named worlds gives exactly what the generators give.
TEST(ScenarioTest, EachKindIsItsGeneratorWithItsDefaultSurvey) {
  ScenarioOptions o;
  o.seed = 4;
  MineOptions m;
  m.seed = 4;
  const GeneratedScenario mine = GenerateScenario(o);
  EXPECT_EQ(mine.world.size(), GenerateRoomAndPillarMine(m).size());
  EXPECT_EQ(mine.map.size(), mine.world.size());
  ASSERT_EQ(mine.stations.size(), 42u);
  EXPECT_EQ(mine.stations.front().pose.x, MineSurveyStations(m).front().pose.x);
  EXPECT_EQ(mine.name, "mine seed 4");

  o.kind = "mockup";
  const GeneratedScenario mockup = GenerateScenario(o);
  const MockupWorld expected = GenerateIndoorMockup(4);
  EXPECT_EQ(mockup.map.size(), expected.map.size());
  EXPECT_EQ(mockup.world.size(), expected.World().size());
  EXPECT_GT(mockup.world.size(), mockup.map.size());  // the clutter is in the world only
  EXPECT_EQ(mockup.stations.size(), 16u);

  o.kind = "loop";
  o.stations = 10;
  EXPECT_EQ(GenerateScenario(o).stations.size(), 10u);
  o.kind = "research";
  o.stations = 0;
  EXPECT_EQ(GenerateScenario(o).stations.size(), 33u);
}

TEST(ScenarioTest, BadOptionsAreRefusedWithAReason) {
  ScenarioOptions o;
  o.kind = "castle";
  EXPECT_NE(ValidateScenarioOptions(o).find("castle"), std::string::npos);
  EXPECT_THROW(GenerateScenario(o), std::invalid_argument);
  o.kind = "mine";
  o.mine.pillar_size = -1.0;
  EXPECT_FALSE(ValidateScenarioOptions(o).empty());
}

}  // namespace
}  // namespace minenav
