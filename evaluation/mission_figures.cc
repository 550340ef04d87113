#include "evaluation/mission_figures.h"

#include <algorithm>
#include <cmath>

#include "common/pose_at_time.h"

namespace minenav {

Distribution Summarize(std::vector<double> values) {
  Distribution d;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  d.count = static_cast<int>(n);
  double sum = 0.0;
  for (const double v : values) sum += v;
  d.mean = sum / static_cast<double>(n);
  d.median = n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  // Nearest rank: the ceil(0.95 n)-th smallest value.
  const size_t rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(n)));
  d.p95 = values[std::clamp<size_t>(rank, 1, n) - 1];
  d.max = values.back();
  return d;
}

// ----------------------------------------------------------------------------- explored area

namespace {

// Does the wall cross the horizontal line through y (half-open: one end strictly above)?
// Then where.
std::optional<double> CrossingX(const Segment& s, double y) {
  if ((s.a.y() > y) == (s.b.y() > y)) return std::nullopt;
  return s.a.x() + (y - s.a.y()) * (s.b.x() - s.a.x()) / (s.b.y() - s.a.y());
}

}  // namespace

bool FreeByParity(const std::vector<Segment>& walls, const Eigen::Vector2d& p) {
  bool inside = false;
  for (const Segment& s : walls) {
    const std::optional<double> x = CrossingX(s, p.y());
    if (x && *x > p.x()) inside = !inside;
  }
  return inside;
}

AreaGrid MakeAreaGrid(const std::vector<Segment>& true_walls,
                      const std::function<bool(const Eigen::Vector2d&)>& known_free, const Eigen::Vector2d& lo,
                      const Eigen::Vector2d& hi, double cell) {
  AreaGrid g;
  g.frame.x0 = lo.x();
  g.frame.y0 = lo.y();
  g.frame.cell = cell;
  g.frame.nx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)));
  g.frame.ny = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)));
  g.truly_free.assign(static_cast<size_t>(g.frame.size()), 0);
  g.known_free.assign(static_cast<size_t>(g.frame.size()), 0);
  std::vector<double> crossings;
  for (int iy = 0; iy < g.frame.ny; ++iy) {
    const double y = g.frame.y0 + (iy + 0.5) * cell;
    crossings.clear();
    for (const Segment& s : true_walls)
      if (const std::optional<double> x = CrossingX(s, y)) crossings.push_back(*x);
    std::sort(crossings.begin(), crossings.end());
    size_t at_or_left = 0;  // crossings with x <= the centre
    for (int ix = 0; ix < g.frame.nx; ++ix) {
      const Eigen::Vector2d c(g.frame.x0 + (ix + 0.5) * cell, y);
      while (at_or_left < crossings.size() && crossings[at_or_left] <= c.x()) ++at_or_left;
      const size_t i = static_cast<size_t>(g.frame.Index(ix, iy));
      g.truly_free[i] = (crossings.size() - at_or_left) % 2 == 1 ? 1 : 0;
      g.known_free[i] = known_free(c) ? 1 : 0;
    }
  }
  return g;
}

AreaFigures MeasureArea(const AreaGrid& grid) {
  AreaFigures a;
  a.cell_m = grid.frame.cell;
  const double cell_area = grid.frame.cell * grid.frame.cell;
  for (size_t i = 0; i < grid.truly_free.size(); ++i) {
    const bool t = grid.truly_free[i] != 0, k = grid.known_free[i] != 0;
    a.true_free_m2 += t ? cell_area : 0.0;
    a.known_free_m2 += k ? cell_area : 0.0;
    a.explored_m2 += t && k ? cell_area : 0.0;
    a.falsely_free_m2 += k && !t ? cell_area : 0.0;
  }
  a.explored_fraction = a.true_free_m2 > 0.0 ? a.explored_m2 / a.true_free_m2 : 0.0;
  return a;
}

std::vector<std::vector<Eigen::Vector2d>> CellRuns(const AreaGrid& grid, bool truly_free, bool known_free) {
  std::vector<std::vector<Eigen::Vector2d>> out;
  const GridFrame& f = grid.frame;
  auto wanted = [&](int ix, int iy) {
    const size_t i = static_cast<size_t>(f.Index(ix, iy));
    return (grid.truly_free[i] != 0) == truly_free && (grid.known_free[i] != 0) == known_free;
  };
  for (int iy = 0; iy < f.ny; ++iy)
    for (int ix = 0; ix < f.nx;) {
      if (!wanted(ix, iy)) {
        ++ix;
        continue;
      }
      const int start = ix;
      while (ix < f.nx && wanted(ix, iy)) ++ix;
      const Eigen::Vector2d a = f.CellMin(start, iy), b = f.CellMin(ix, iy + 1);
      out.push_back({a, {b.x(), a.y()}, b, {a.x(), b.y()}});
    }
  return out;
}

// ------------------------------------------------------------------------------- pose error

namespace {

const std::vector<StampedPose>& SortedByTime(const std::vector<StampedPose>& poses, std::vector<StampedPose>* copy) {
  const auto earlier = [](const StampedPose& a, const StampedPose& b) { return a.utime < b.utime; };
  if (std::is_sorted(poses.begin(), poses.end(), earlier)) return poses;
  *copy = poses;
  std::stable_sort(copy->begin(), copy->end(), earlier);
  return *copy;
}

}  // namespace

PoseErrorFigures ComparePoses(const std::vector<StampedPose>& poses, const std::vector<StampedPose>& truth_in,
                              int64_t max_gap_us) {
  std::vector<StampedPose> copy;
  const std::vector<StampedPose>& truth = SortedByTime(truth_in, &copy);
  PoseErrorFigures f;
  double sum = 0.0, sum_sq = 0.0, sum_heading = 0.0;
  for (const StampedPose& p : poses) {
    const std::optional<Pose2> t = PoseAtTime(truth, p.utime, max_gap_us);
    if (!t) {
      ++f.unmatched;
      continue;
    }
    const double e = TranslationDistance(p.pose, *t), h = HeadingDistance(p.pose, *t);
    ++f.compared;
    sum += e;
    sum_sq += e * e;
    sum_heading += h;
    if (e > f.max_m || f.compared == 1) {
      f.max_m = e;
      f.worst_utime = p.utime;
    }
    f.max_heading_rad = std::max(f.max_heading_rad, h);
  }
  if (f.compared > 0) {
    const double n = f.compared;
    f.mean_m = sum / n;
    f.rms_m = std::sqrt(sum_sq / n);
    f.mean_heading_rad = sum_heading / n;
  }
  return f;
}

std::vector<StampedPose> AlignToTruthAtStart(const std::vector<StampedPose>& track,
                                             const std::vector<StampedPose>& truth_in, int64_t max_gap_us) {
  std::vector<StampedPose> copy;
  const std::vector<StampedPose>& truth = SortedByTime(truth_in, &copy);
  for (const StampedPose& p : track) {
    const std::optional<Pose2> t = PoseAtTime(truth, p.utime, max_gap_us);
    if (!t) continue;
    const Pose2 world_T_track = *t * p.pose.inverse();
    std::vector<StampedPose> out = track;
    for (StampedPose& q : out) q.pose = world_T_track * q.pose;
    return out;
  }
  return track;
}

// -------------------------------------------------------------------------------- cut depth

DepthFigures MeasureFaceAdvance(const Segment& face, const Eigen::Vector2d& advance, const StaticSegmentIndex& before,
                                const StaticSegmentIndex& after, const CutDepthOptions& options) {
  DepthFigures d;
  const int n = std::max(1, options.rays);
  const Eigen::Vector2d dir = advance.normalized();
  const double range = options.back_off + options.reach;
  std::vector<double> depths;
  for (int i = 0; i < n; ++i) {
    const double f = n == 1 ? 0.5 * (options.inner_from + options.inner_to)
                            : options.inner_from + (options.inner_to - options.inner_from) * i / (n - 1);
    const Eigen::Vector2d origin = face.a + f * (face.b - face.a) - options.back_off * dir;
    ++d.rays;
    const std::optional<RayHit> b = before.CastRayDir(origin, dir, range);
    const std::optional<RayHit> a = after.CastRayDir(origin, dir, range);
    if (b && a) depths.push_back(a->range - b->range);
  }
  d.hits = static_cast<int>(depths.size());
  if (depths.empty()) return d;
  const Distribution s = Summarize(depths);
  d.median = s.median;
  d.min = *std::min_element(depths.begin(), depths.end());
  d.max = s.max;
  return d;
}

// ---------------------------------------------------------------------------- planning times

namespace {

// A decimal number "123" or "123.45" (at most 12 digits either side of the point) that is the
// whole of `text`.
std::optional<double> Decimal(const std::string& text) {
  const size_t point = text.find('.');
  const std::string whole = text.substr(0, point);
  const std::string fraction = point == std::string::npos ? "" : text.substr(point + 1);
  auto digits = [](const std::string& d) {
    return !d.empty() && d.size() <= 12 && d.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!digits(whole) || (point != std::string::npos && !digits(fraction))) return std::nullopt;
  return std::stod(text);
}

}  // namespace

std::optional<PlannerSearch> ParsePlannerStatus(const std::string& status) {
  // The answer is the last "ok: ..." of the line (a replan's prefix names poses and pieces):
  // "ok: L m, ..., T ms on map version V".
  const size_t at = status.rfind("ok: ");
  if (at == std::string::npos || status.size() > 4096) return std::nullopt;
  const std::string answer = status.substr(at + 4);
  const size_t metres = answer.find(" m, ");
  const std::string kTail = " ms on map version ";
  const size_t tail = answer.rfind(kTail);
  if (metres == std::string::npos || tail == std::string::npos || tail < metres) return std::nullopt;
  // V: the digits after the tail, then nothing but spaces.
  std::string version = answer.substr(tail + kTail.size());
  version.erase(version.find_last_not_of(" \t\r\n") + 1);
  if (version.empty() || version.size() > 15 || version.find_first_not_of("0123456789") != std::string::npos)
    return std::nullopt;
  // T: the number before the tail, after ", ".
  const size_t comma = answer.rfind(", ", tail);
  if (comma == std::string::npos || comma < metres + 2) return std::nullopt;
  const std::optional<double> length = Decimal(answer.substr(0, metres));
  const std::optional<double> ms = Decimal(answer.substr(comma + 2, tail - comma - 2));
  if (!length || !ms) return std::nullopt;
  PlannerSearch s;
  s.length_m = *length;
  s.ms = *ms;
  s.map_version = std::stoll(version);
  s.replanned = status.rfind("replanned:", 0) == 0;
  return s;
}

}  // namespace minenav
