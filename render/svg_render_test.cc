// The SVG writer's markers (the mission picture's stations, cut targets, the start, where a map
// is worst): each shape drawn, its text beside it, in the legend, and inside the view.

#include "render/svg_render.h"

#include <gtest/gtest.h>


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
  // The cross at (30, 20) is inside the drawing: the view grew to hold it. The drawing's frame
  // is the first rect with fill="none"; the cross the path that starts with its first stroke.
  auto number_after = [&](size_t from, const std::string& key) {
    const size_t at = svg.find(key, from) + key.size();
    return std::stod(svg.substr(at, svg.find_first_of("\" ", at) - at));
  };
  const size_t frame = svg.rfind("<rect", svg.find("fill=\"none\""));
  const double right = number_after(frame, "x=\"") + number_after(frame, "width=\"");
  const size_t group = svg.find("<g stroke=\"#f00\"");
  ASSERT_NE(group, std::string::npos);
  const size_t cross = svg.find("<path d=\"M", group);
  const size_t l = svg.find('L', cross);
  const double cross_right = std::stod(svg.substr(l + 1, svg.find(' ', l) - l - 1));
  EXPECT_LT(cross_right, right);
}

}  // namespace
}  // namespace minenav
