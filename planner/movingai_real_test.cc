// The search core against the Moving AI benchmark (shared/datasets/movingai, see SOURCES.md
// there): on every 10th scenario of each shared map (every n/30-th of the two 512 x 512 room
// maps, whose long paths take most of the time: 30 scenarios spread over all their buckets) the grid A* length equals the published
// optimum within 1e-3. Built only where the datasets are; a missing file fails.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dataset_readers/dataset_path.h"
#include "planner/grid_astar.h"
#include "planner/movingai.h"

namespace minenav {
namespace {

class MovingAiRealTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MovingAiRealTest, EveryTenthScenarioHasThePublishedOptimalLength) {
  const std::string map_path = logger_test::Dataset(std::string("movingai/") + GetParam());
  const OccupancyGrid grid = LoadMovingAiMap(map_path);
  const auto scenarios = LoadMovingAiScenarios(map_path + ".scen");
  CheckScenariosFitMap(scenarios, grid, map_path + ".scen");
  ASSERT_GE(scenarios.size(), 100u);
  GridAStar astar(grid);
  int checked = 0;
  const size_t stride = std::max<size_t>(10, scenarios.size() / 30);
  for (size_t i = 0; i < scenarios.size(); i += stride) {
    const MovingAiScenario& s = scenarios[i];
    const GridSearchResult r = astar.Plan(s.start, s.goal);
    ASSERT_EQ(r.status, SearchStatus::kFound) << "scenario " << i << ": " << r.reason;
    EXPECT_NEAR(r.length, s.optimal_length, 1e-3) << "scenario " << i;
    ++checked;
  }
  EXPECT_GE(checked, 16);
}

INSTANTIATE_TEST_SUITE_P(SharedMaps, MovingAiRealTest,
                         ::testing::Values("dao/arena.map", "dao/den312d.map", "dao/lak303d.map",
                                           "room/8room_000.map", "room/32room_000.map"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           std::string name = p.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace minenav
