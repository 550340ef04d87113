// The SVG writer's markers (the mission picture's stations, cut targets, the start, where a map
// is worst): each shape drawn, its text beside it, in the legend, and inside the view.

#include "render/svg_render.h"

#include <gtest/gtest.h>

#include <regex>

namespace minenav {
namespace {

int Count(const std::string& s, const std::string& needle) {
  int n = 0;
  for (size_t at = s.find(needle); at != std::string::npos; at = s.find(needle, at + 1)) ++n;
  return n;
}

TEST(SvgRender, MarkersOfEachShapeWithTextsAndLegend) {
  SvgScene scene;
  scene.lines.push_back({"walls", "#333", 1.5, {Segment({0, 0}, {10, 0})}, {}});
  SvgMarkers stations{"stations", "#00f", SvgMarkers::Shape::kCircle, 4.0, true,
                      {Pose2(1, 1, 0), Pose2(2, 2, 1)}, {"1", "2"}};
  SvgMarkers start{"start", "#000", SvgMarkers::Shape::kSquare, 5.0, false, {Pose2(3, 3, 0)}, {}};
  SvgMarkers targets{"targets", "#f80", SvgMarkers::Shape::kDiamond, 5.0, false, {Pose2(4, 4, 0)}, {"box"}};
  // Far outside the walls: markers widen the view.
  SvgMarkers worst{"worst", "#f00", SvgMarkers::Shape::kCross, 5.0, false, {Pose2(30, 20, 0)}, {}};
  scene.markers = {stations, start, targets, worst};
  const std::string svg = RenderSvg(scene);
  EXPECT_EQ(Count(svg, "<circle"), 2 + 1);  // two stations, one in the legend
  EXPECT_EQ(Count(svg, "<rect x="), 1 + 1 + 2);  // the start, its legend entry, the frame and the clip area
  for (const std::string text : {">1</text>", ">2</text>", ">box</text>", ">stations</text>", ">start</text>",
                                 ">targets</text>", ">worst</text>", ">walls</text>"})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  // The cross at (30, 20) is inside the drawing: the view grew to hold it.
  const std::regex frame(R"re(<rect x="([0-9.]+)" y="([0-9.]+)" width="([0-9.]+)" height="([0-9.]+)" fill="none")re");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, frame));
  const double right = std::stod(m[1].str()) + std::stod(m[3].str());
  const std::regex cross(R"re(<path d="M([0-9.]+) ([0-9.]+)L([0-9.]+) ([0-9.]+)M)re");
  ASSERT_TRUE(std::regex_search(svg, m, cross));
  EXPECT_LT(std::stod(m[3].str()), right);
}

}  // namespace
}  // namespace minenav
