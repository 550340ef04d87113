#pragma once
// A picture of a run a person can open in a browser: world walls, a surveyed map, scan
// points at their poses, trajectories (truth, odometry, estimates), a grid, a scale bar
// and a legend. Plain C++ (no LCM): `log_tool render` gathers the layers from a log.
// World x to the right, y up; the SVG flips y.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/pose2.h"

namespace minenav {

struct SvgPolyline {
  std::vector<Eigen::Vector2d> points;
  bool closed = false;
};

// Line work: world walls, map segments, contours.
struct SvgLineLayer {
  std::string label;   // legend text; empty = not in the legend
  std::string color;   // any SVG colour
  double width_px = 1.5;
  std::vector<Segment> segments;
  std::vector<SvgPolyline> polylines;
};

// Scan points, drawn as dots.
struct SvgPointLayer {
  std::string label;
  std::string color;
  double radius_px = 0.9;
  double opacity = 0.6;
  std::vector<Eigen::Vector2d> points;
};

// A vehicle trajectory: a polyline through the poses, and a marker with a heading tick
// at each pose when `markers` is set.
struct SvgTrajectory {
  std::string label;
  std::string color;
  double width_px = 1.5;
  bool dashed = false;
  bool markers = true;
  std::vector<Pose2> poses;
};

// Thin links between corresponding poses of two trajectories (e.g. truth and the
// initial estimate of the same scan), so the error of each is visible.
struct SvgLinks {
  std::string label;
  std::string color;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> links;
};

// Filled areas (known free space, ...), drawn under everything else, without outline.
struct SvgArea {
  std::string label;
  std::string color;
  double opacity = 0.2;
  std::vector<std::vector<Eigen::Vector2d>> polygons;
};

// Markers at places (scan stations, cut targets, where a map is worst): a shape, an optional
// heading tick, and an optional text beside each.
struct SvgMarkers {
  enum class Shape { kCircle, kSquare, kDiamond, kCross };
  std::string label;
  std::string color;
  Shape shape = Shape::kCircle;
  double size_px = 5.0;        // half the shape's width
  bool heading_ticks = false;  // a tick from the centre along each pose's heading
  std::vector<Pose2> poses;
  std::vector<std::string> texts;  // texts[i] is written beside poses[i]; may be shorter
};

struct SvgScene {
  std::string title;
  std::vector<std::string> notes;  // extra lines under the title
  std::vector<SvgPointLayer> points;       // drawn first
  std::vector<SvgLineLayer> lines;         // then walls and maps over the points
  std::vector<SvgLinks> links;
  std::vector<SvgTrajectory> trajectories; // on top
  std::vector<SvgArea> areas;              // under everything
  std::vector<SvgMarkers> markers;         // over the trajectories
};

struct SvgRenderOptions {
  double width_px = 1400.0;   // px, width of the drawing area (height follows the aspect ratio)
  double max_height_px = 1400.0;  // px; the scale shrinks to respect it
  double margin_px = 60.0;    // px around the drawing area
  double legend_width_px = 340.0;  // px, column at the right for the legend
  bool grid = true;           // light grid at the scale bar's spacing
};

// A "nice" length (1, 2 or 5 times a power of ten) close to `approx`, for scale bars
// and grids. approx must be > 0.
double NiceLength(double approx);

std::string RenderSvg(const SvgScene& scene, const SvgRenderOptions& options = {});

}  // namespace minenav
