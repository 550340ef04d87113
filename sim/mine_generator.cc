#include "sim/mine_generator.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "common/angle.h"

namespace minenav {

namespace {

using Vec = Eigen::Vector2d;

// Recursive midpoint displacement (5.2.1): split a -> b at its midpoint moved along the
// edge normal by U[-d, d], halving d at each level, until pieces are shorter than max_len.
void SplitEdge(const Vec& a, const Vec& b, double d, double max_len, int depth, std::mt19937_64& rng,
               std::vector<Segment>* out) {
  const Vec e = b - a;
  const double len = e.norm();
  if (len < max_len || depth > 40) {
    out->emplace_back(a, b);
    return;
  }
  const Vec normal(-e.y() / len, e.x() / len);
  std::uniform_real_distribution<double> u(-d, d);
  const double offset = d > 0.0 ? u(rng) : 0.0;
  const Vec m = 0.5 * (a + b) + offset * normal;
  SplitEdge(a, m, 0.5 * d, max_len, depth + 1, rng, out);
  SplitEdge(m, b, 0.5 * d, max_len, depth + 1, rng, out);
}

// A closed loop through `corners` (in order), every edge split as above.
void AddLoop(const std::vector<Vec>& corners, double d, double max_len, std::mt19937_64& rng,
             std::vector<Segment>* out) {
  for (size_t i = 0; i < corners.size(); ++i)
    SplitEdge(corners[i], corners[(i + 1) % corners.size()], d, max_len, 0, rng, out);
}

// A square of side `size` with lower-left corner `lo`, counter-clockwise, unsplit.
void AddSquare(const Vec& lo, double size, std::vector<Segment>* out) {
  const Vec c[4] = {lo, lo + Vec(size, 0), lo + Vec(size, size), lo + Vec(0, size)};
  for (int i = 0; i < 4; ++i) out->emplace_back(c[i], c[(i + 1) % 4]);
}

// `count` poses evenly spaced along a polyline (first at its start, last at its end),
// heading along the polyline plus U[-variation, variation].
std::vector<Station> StationsAlong(const std::vector<Vec>& path, int count, double variation, uint64_t seed,
                                   bool closed, double max_spacing = 0.0) {
  std::vector<Vec> pts = path;
  if (closed) pts.push_back(path.front());
  std::vector<double> cum{0.0};
  for (size_t i = 1; i < pts.size(); ++i) cum.push_back(cum.back() + (pts[i] - pts[i - 1]).norm());
  const double total = cum.back();
  std::mt19937_64 rng(seed ^ 0x5eed5eedULL);
  std::uniform_real_distribution<double> u(-variation, variation);
  std::vector<Station> out;
  if (count <= 0 || pts.size() < 2) return out;
  // Open path: ends included. Closed loop: `count` equal gaps, the last before the start.
  double spacing = closed ? total / count : (count > 1 ? total / (count - 1) : 0.0);
  if (max_spacing > 0.0 && !closed) spacing = std::min(spacing, max_spacing);
  size_t seg = 1;
  for (int k = 0; k < count; ++k) {
    const double s = std::min(total, k * spacing);
    while (seg + 1 < pts.size() && cum[seg] < s) ++seg;
    const Vec a = pts[seg - 1], b = pts[seg];
    const double seg_len = cum[seg] - cum[seg - 1];
    const double t = seg_len > 0.0 ? (s - cum[seg - 1]) / seg_len : 0.0;
    const Vec p = a + t * (b - a);
    const double heading = std::atan2(b.y() - a.y(), b.x() - a.x()) + (variation > 0.0 ? u(rng) : 0.0);
    Station st;
    st.pose = Pose2(p.x(), p.y(), NormalizeAngle(heading));
    out.push_back(st);
  }
  return out;
}

// Serpentine through entries at ys (ascending), between x_west and x_east.
std::vector<Vec> Serpentine(const std::vector<double>& ys, double x_west, double x_east) {
  std::vector<Vec> path;
  for (size_t k = 0; k < ys.size(); ++k) {
    const bool east = k % 2 == 0;
    path.emplace_back(east ? x_west : x_east, ys[k]);
    path.emplace_back(east ? x_east : x_west, ys[k]);
  }
  return path;
}

void Require(const std::string& why) {
  if (!why.empty()) throw std::invalid_argument(why);
}

}  // namespace

std::string ValidateMineOptions(const MineOptions& o) {
  std::ostringstream why;
  if (o.pillar_rows < 1 || o.pillar_cols < 1)
    why << "pillar_rows and pillar_cols must be >= 1 (got " << o.pillar_rows << ", " << o.pillar_cols << ")";
  else if (!(o.pillar_size > 0.0) || !std::isfinite(o.pillar_size))
    why << "pillar_size must be > 0 m (got " << o.pillar_size << ")";
  else if (!(o.room_width > 0.0) || !std::isfinite(o.room_width))
    why << "room_width must be > 0 m (got " << o.room_width << ")";
  else if (!(o.max_segment_length > 0.0) || !std::isfinite(o.max_segment_length))
    why << "max_segment_length must be > 0 m (got " << o.max_segment_length << ")";
  else if (!(o.midpoint_displacement >= 0.0) || 4.0 * o.midpoint_displacement >= o.room_width)
    why << "midpoint_displacement must be in [0, room_width / 4) m (got " << o.midpoint_displacement << ")";
  else if (static_cast<double>(o.pillar_rows) * o.pillar_cols * 4.0 * o.pillar_size / o.max_segment_length > 5e7)
    why << "mine too large: more than 50 million segments";
  return why.str();
}

Eigen::Vector2d MinePanelSize(const MineOptions& o) {
  const double pitch = o.pillar_size + o.room_width;
  return {o.pillar_cols * pitch + o.room_width, o.pillar_rows * pitch + o.room_width};
}

std::vector<Segment> GenerateRoomAndPillarMine(const MineOptions& o) {
  Require(ValidateMineOptions(o));
  std::mt19937_64 rng(o.seed);
  const double pitch = o.pillar_size + o.room_width;
  const Vec size = MinePanelSize(o);
  std::vector<Segment> out;
  AddLoop({Vec(0, 0), Vec(size.x(), 0), size, Vec(0, size.y())}, o.midpoint_displacement,
          o.max_segment_length, rng, &out);
  for (int r = 0; r < o.pillar_rows; ++r) {
    for (int c = 0; c < o.pillar_cols; ++c) {
      const Vec lo(o.room_width + c * pitch, o.room_width + r * pitch);
      const double p = o.pillar_size;
      AddLoop({lo, lo + Vec(p, 0), lo + Vec(p, p), lo + Vec(0, p)}, o.midpoint_displacement,
              o.max_segment_length, rng, &out);
    }
  }
  return out;
}

std::vector<Station> MineSurveyStations(const MineOptions& o, int count, double heading_variation, double spacing) {
  Require(ValidateMineOptions(o));
  const double pitch = o.pillar_size + o.room_width;
  const Vec size = MinePanelSize(o);
  std::vector<double> ys;
  for (int k = 0; k <= o.pillar_rows; ++k) ys.push_back(0.5 * o.room_width + k * pitch);
  return StationsAlong(Serpentine(ys, 0.5 * o.room_width, size.x() - 0.5 * o.room_width), count,
                       heading_variation, o.seed, false, spacing);
}

std::vector<Station> LoopStations(const MineOptions& o, int count, int pillar_row, int pillar_col,
                                  double heading_variation) {
  Require(ValidateMineOptions(o));
  if (pillar_row < 0 || pillar_row >= o.pillar_rows || pillar_col < 0 || pillar_col >= o.pillar_cols)
    throw std::invalid_argument("LoopStations: pillar (" + std::to_string(pillar_row) + ", " +
                                std::to_string(pillar_col) + ") is not in the panel");
  const double pitch = o.pillar_size + o.room_width;
  const Vec lo(o.room_width + pillar_col * pitch - 0.5 * o.room_width,
               o.room_width + pillar_row * pitch - 0.5 * o.room_width);
  const double side = pitch;
  return StationsAlong({lo, lo + Vec(side, 0), lo + Vec(side, side), lo + Vec(0, side)}, count,
                       heading_variation, o.seed + 17, true);
}

// ---- research mine (5.3) ----

namespace {

struct ResearchLayout {
  std::vector<double> pillar_x0, pillar_w;  // per column
  std::vector<double> pillar_y0, pillar_h;  // per row
  std::vector<double> crosscut_x;           // centreline x of each north-south entry (cols + 1)
  std::vector<double> entry_y;              // centreline y of each east-west entry (rows + 1)
  std::vector<double> crosscut_w, entry_w;  // widths
  Vec size;
};

ResearchLayout Layout(const ResearchMineOptions& o, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> pillar(o.pillar_size_min, o.pillar_size_max);
  std::uniform_real_distribution<double> entry(o.entry_width_min, o.entry_width_max);
  ResearchLayout l;
  double x = 0.0;
  for (int c = 0; c <= o.pillar_cols; ++c) {
    const double w = entry(rng);
    l.crosscut_w.push_back(w);
    l.crosscut_x.push_back(x + 0.5 * w);
    x += w;
    if (c < o.pillar_cols) {
      l.pillar_x0.push_back(x);
      l.pillar_w.push_back(pillar(rng));
      x += l.pillar_w.back();
    }
  }
  double y = 0.0;
  for (int r = 0; r <= o.pillar_rows; ++r) {
    const double w = entry(rng);
    l.entry_w.push_back(w);
    l.entry_y.push_back(y + 0.5 * w);
    y += w;
    if (r < o.pillar_rows) {
      l.pillar_y0.push_back(y);
      l.pillar_h.push_back(pillar(rng));
      y += l.pillar_h.back();
    }
  }
  l.size = Vec(x, y);
  return l;
}

// How far (m) a wall may stand inside its nominal line: corner jitter plus fractal offsets.
double WallMargin(const ResearchMineOptions& o) { return o.corner_jitter + 2.0 * o.midpoint_displacement + 0.05; }

}  // namespace

std::string ValidateResearchMineOptions(const ResearchMineOptions& o) {
  std::ostringstream why;
  const double clear = 0.5 * o.entry_width_min - WallMargin(o) - std::max(o.crib_size, o.post_size);
  if (o.pillar_rows < 1 || o.pillar_cols < 1)
    why << "pillar_rows and pillar_cols must be >= 1";
  else if (!(o.pillar_size_min > 0.0) || !(o.pillar_size_max >= o.pillar_size_min))
    why << "pillar sizes must satisfy 0 < min <= max (got " << o.pillar_size_min << ", " << o.pillar_size_max << ")";
  else if (!(o.entry_width_min > 0.0) || !(o.entry_width_max >= o.entry_width_min))
    why << "entry widths must satisfy 0 < min <= max (got " << o.entry_width_min << ", " << o.entry_width_max << ")";
  else if (!(o.corner_jitter >= 0.0) || !(o.midpoint_displacement >= 0.0))
    why << "corner_jitter and midpoint_displacement must be >= 0";
  else if (2.0 * (o.corner_jitter + 2.0 * o.midpoint_displacement) >= 0.5 * o.pillar_size_min)
    why << "corner_jitter + 2 * midpoint_displacement too large for pillar_size_min";
  else if (!(o.max_segment_length > 0.0))
    why << "max_segment_length must be > 0 m";
  else if (!(o.crib_size > 0.0) || !(o.post_size > 0.0) || !(o.cribs_per_entry >= 0.0) || !(o.posts_per_entry >= 0.0))
    why << "crib_size, post_size must be > 0 and cribs/posts per entry >= 0";
  else if (clear < 0.3)
    why << "entries too narrow for cribs: entry_width_min / 2 - (corner_jitter + 2 * midpoint_displacement + 0.05)"
        << " - crib/post size = " << clear << " m leaves less than 0.3 m to the centreline";
  return why.str();
}

std::vector<Segment> GenerateResearchMine(const ResearchMineOptions& o) {
  Require(ValidateResearchMineOptions(o));
  std::mt19937_64 rng(o.seed);
  const ResearchLayout l = Layout(o, rng);
  std::uniform_real_distribution<double> jitter(-o.corner_jitter, o.corner_jitter);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto j = [&]() { return o.corner_jitter > 0.0 ? jitter(rng) : 0.0; };

  std::vector<Segment> out;
  AddLoop({Vec(0, 0), Vec(l.size.x(), 0), l.size, Vec(0, l.size.y())}, o.midpoint_displacement,
          o.max_segment_length, rng, &out);
  for (int r = 0; r < o.pillar_rows; ++r) {
    for (int c = 0; c < o.pillar_cols; ++c) {
      const double x0 = l.pillar_x0[c], x1 = x0 + l.pillar_w[c];
      const double y0 = l.pillar_y0[r], y1 = y0 + l.pillar_h[r];
      std::vector<Vec> corners{Vec(x0 + j(), y0 + j()), Vec(x1 + j(), y0 + j()), Vec(x1 + j(), y1 + j()),
                               Vec(x0 + j(), y1 + j())};
      AddLoop(corners, o.midpoint_displacement, o.max_segment_length, rng, &out);
    }
  }

  // Crib blocks and posts, in the entries between intersections, beside a wall.
  const double margin = WallMargin(o);
  auto how_many = [&](double mean) {
    const double whole = std::floor(mean);
    return static_cast<int>(whole) + (unit(rng) < mean - whole ? 1 : 0);
  };
  std::vector<std::pair<Vec, double>> placed;  // lower-left corner and side of each block
  auto place = [&](double size, bool along_x, double span0, double span1, double wall_lo, double wall_hi) {
    // Along the entry within [span0 + 1, span1 - 1 - size]; against the low or high wall;
    // at least 0.2 m from any other block (a few tries, else left out).
    const double lo = span0 + 1.0, hi = span1 - 1.0 - size;
    if (hi <= lo) return;
    for (int attempt = 0; attempt < 10; ++attempt) {
      const double s = lo + unit(rng) * (hi - lo);
      const bool low_side = unit(rng) < 0.5;
      const double across = low_side ? wall_lo + margin : wall_hi - margin - size;
      const Vec corner = along_x ? Vec(s, across) : Vec(across, s);
      bool clear = true;
      for (const auto& [c, sz] : placed)
        clear = clear && (corner.x() > c.x() + sz + 0.2 || c.x() > corner.x() + size + 0.2 ||
                          corner.y() > c.y() + sz + 0.2 || c.y() > corner.y() + size + 0.2);
      if (!clear) continue;
      placed.emplace_back(corner, size);
      AddSquare(corner, size, &out);
      return;
    }
  };
  for (int k = 0; k <= o.pillar_rows; ++k) {  // east-west entries, between pillar columns
    const double wall_lo = l.entry_y[k] - 0.5 * l.entry_w[k], wall_hi = l.entry_y[k] + 0.5 * l.entry_w[k];
    for (int c = 0; c < o.pillar_cols; ++c) {
      const double span0 = l.pillar_x0[c], span1 = span0 + l.pillar_w[c];
      for (int n = how_many(o.cribs_per_entry); n > 0; --n) place(o.crib_size, true, span0, span1, wall_lo, wall_hi);
      for (int n = how_many(o.posts_per_entry); n > 0; --n) place(o.post_size, true, span0, span1, wall_lo, wall_hi);
    }
  }
  for (int c = 0; c <= o.pillar_cols; ++c) {  // north-south crosscuts, between pillar rows
    const double wall_lo = l.crosscut_x[c] - 0.5 * l.crosscut_w[c], wall_hi = l.crosscut_x[c] + 0.5 * l.crosscut_w[c];
    for (int r = 0; r < o.pillar_rows; ++r) {
      const double span0 = l.pillar_y0[r], span1 = span0 + l.pillar_h[r];
      for (int n = how_many(o.cribs_per_entry); n > 0; --n) place(o.crib_size, false, span0, span1, wall_lo, wall_hi);
      for (int n = how_many(o.posts_per_entry); n > 0; --n) place(o.post_size, false, span0, span1, wall_lo, wall_hi);
    }
  }
  return out;
}

std::vector<Station> ResearchMineStations(const ResearchMineOptions& o, int count, double heading_variation,
                                          double spacing) {
  Require(ValidateResearchMineOptions(o));
  std::mt19937_64 rng(o.seed);
  const ResearchLayout l = Layout(o, rng);  // same draws as GenerateResearchMine's first ones
  return StationsAlong(Serpentine(l.entry_y, l.crosscut_x.front(), l.crosscut_x.back()), count,
                       heading_variation, o.seed, false, spacing);
}

}  // namespace minenav
