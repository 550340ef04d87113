#pragma once
// Synthetic mine worlds and survey stations.
//
// GenerateRoomAndPillarMine: thesis 5.2.1, "A simple fractal technique was used to add a
// random component to a matrix of squares representing a room-and-pillar coal mine ...
// pillars 12m on a side and 6m wide rooms. Each line segment was split with random error
// added to the midpoint until segment size fell below a threshold, about 2m." We add an
// outer boundary wall one room width outside the outermost pillars (split the same way),
// so every ray from inside the panel hits something.
//
// Layout (metres): the panel spans [0, W] x [0, H] with W = cols * (pillar + room) + room,
// H = rows * (pillar + room) + room. Pillar (r, c) nominally occupies
// [room + c * pitch, room + c * pitch + pillar] x [room + r * pitch, ...], pitch = pillar + room.
// Every wall is a closed loop (each pillar, and the boundary), counter-clockwise.
//
// GenerateResearchMine: thesis 5.3, the Bureau of Mines research mine: "not nearly as
// regular", "many more crib block supports", "2' square timber pillars", rooms "often only
// about 10' to 12' wide". Narrow entries (3-4 m), pillars of varying size with jittered
// corners, crib blocks and timber posts standing in the entries beside the walls.

#include <cstdint>
#include <vector>

#include "common/file_io.h"
#include "common/geometry.h"

namespace minenav {

struct MineOptions {
  int pillar_rows = 2;             // pillars along y
  int pillar_cols = 3;             // pillars along x
  double pillar_size = 12.0;       // m, side of each (nominal) square pillar
  double room_width = 6.0;         // m, width of rooms/entries between pillars
  double max_segment_length = 2.0; // m, edges are split until every segment is shorter
  // m: the first split of an edge moves its midpoint perpendicular to the edge by a value
  // drawn uniformly from [-d, d]; each deeper split halves d (fractal midpoint displacement).
  // The total offset of any wall point from its nominal line is below 2 d.
  double midpoint_displacement = 0.3;
  uint64_t seed = 1;
};

// Returns a one-line reason if the options are unusable, else "".
std::string ValidateMineOptions(const MineOptions& options);

// Throws std::invalid_argument (one line) on invalid options.
std::vector<Segment> GenerateRoomAndPillarMine(const MineOptions& options);

// Width and height (m) of the panel inside its boundary wall.
Eigen::Vector2d MinePanelSize(const MineOptions& options);

// `count` survey stations (default use 42, as in 5.2.1) on the centrelines of the
// east-west entries and the north-south crosscuts at their ends: a serpentine through the
// panel (east along the first entry, north through the end crosscut, west along the next,
// ...), evenly spaced along that path so successive scans overlap (about 4.8 m apart for
// the default 2 x 3 panel and 42 stations). Heading = direction of travel plus a seeded
// uniform offset in [-heading_variation, heading_variation] rad. spacing > 0 (m) caps the
// distance between consecutive stations: in a large panel the survey then covers only the
// first part of the serpentine instead of spreading `count` stations thinly over all of it.
std::vector<Station> MineSurveyStations(const MineOptions& options, int count = 42,
                                        double heading_variation = 0.6, double spacing = 0.0);

// `count` stations evenly spaced around the pillar (row, col), on the centrelines of the
// four rooms around it, counter-clockwise, for loop-closure tests: the last station is
// one spacing before the first, so the sequence closes the loop.
std::vector<Station> LoopStations(const MineOptions& options, int count, int pillar_row = 0,
                                  int pillar_col = 0, double heading_variation = 0.6);

struct ResearchMineOptions {
  int pillar_rows = 3;
  int pillar_cols = 4;
  double pillar_size_min = 8.0;    // m, nominal pillar side drawn uniformly in [min, max]
  double pillar_size_max = 14.0;   // m
  double entry_width_min = 3.0;    // m, each entry/crosscut width drawn in [min, max]
  double entry_width_max = 4.0;    // m
  double corner_jitter = 0.25;     // m, each pillar corner moved uniformly in [-j, j] in x and y
  double max_segment_length = 1.0; // m
  double midpoint_displacement = 0.1;   // m, as MineOptions::midpoint_displacement
  double crib_size = 0.6;          // m, side of a square crib block
  double cribs_per_entry = 1.5;    // mean number of crib blocks per entry segment between pillars
  double post_size = 0.3;          // m, side of a square timber post
  double posts_per_entry = 1.0;    // mean number of timber posts per entry segment
  uint64_t seed = 1;
};

std::string ValidateResearchMineOptions(const ResearchMineOptions& options);

// Walls, crib blocks and posts (all closed loops). Throws std::invalid_argument on bad options.
// Cribs and posts stand beside the walls and leave the entry centreline clear by at least
// 0.3 m, so the stations below are always in free space.
std::vector<Segment> GenerateResearchMine(const ResearchMineOptions& options);

// Serpentine survey like MineSurveyStations, on the (irregular) entry centrelines.
std::vector<Station> ResearchMineStations(const ResearchMineOptions& options, int count = 33,
                                          double heading_variation = 0.6, double spacing = 0.0);

}  // namespace minenav
