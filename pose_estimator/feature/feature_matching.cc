#include "pose_estimator/feature/feature_matching.h"

#include <algorithm>
#include <cmath>

#include "common/config.h"

namespace minenav {
namespace {

double AngleDiff(double a, double b) { return std::abs(NormalizeAngle(a - b)); }

double Bearing(const Eigen::Vector2d& p) { return std::atan2(p.y(), p.x()); }

// Bearing slack from a position error at this range.
double PositionSlack(double range, double poserr) { return std::atan2(poserr, std::max(range, 1e-3)); }

struct Search {
  const std::vector<Feature>& sensed;
  const std::vector<Feature>& model;
  const MatchingOptions& o;
  std::vector<FeaturePair> pairs;
  std::vector<std::vector<char>> compatible;  // [i][j]: binary-consistent, distinct features
  std::vector<int> out_len, in_len;
  std::vector<int> current, best;
  long best_points = -1;
  int nodes = 0;
  bool complete = true;

  long Points(const std::vector<int>& set) const {
    long s = 0;
    for (int i : set) s += sensed[static_cast<size_t>(pairs[static_cast<size_t>(i)].sensed)].num_points;
    return s;
  }

  int ModelOffset(int i) const {
    const int m = static_cast<int>(model.size());
    const int first = pairs[static_cast<size_t>(current.front())].model;
    return (pairs[static_cast<size_t>(i)].model - first + m) % m;
  }

  void Consider() {
    const long points = Points(current);
    if (current.size() > best.size() || (current.size() == best.size() && points > best_points)) {
      best = current;
      best_points = points;
    }
  }

  void Extend(int from) {
    Consider();
    const int last = current.back();
    const int last_offset = ModelOffset(last);
    for (int j = from; j < static_cast<int>(pairs.size()); ++j) {
      if (nodes >= o.max_search_nodes) {
        complete = false;
        return;
      }
      const FeaturePair& q = pairs[static_cast<size_t>(j)];
      if (q.sensed <= pairs[static_cast<size_t>(last)].sensed) continue;
      // Bound: even the longest pairwise chain out of j cannot beat the best (ties may
      // still win on points, so only strictly shorter branches are cut).
      if (static_cast<int>(current.size()) + out_len[static_cast<size_t>(j)] <
          static_cast<int>(best.size())) {
        continue;
      }
      if (ModelOffset(j) <= last_offset) continue;
      bool ok = true;
      for (int i : current) ok = ok && compatible[static_cast<size_t>(i)][static_cast<size_t>(j)];
      if (!ok) continue;
      ++nodes;
      current.push_back(j);
      Extend(j + 1);
      current.pop_back();
    }
  }
};

}  // namespace

bool UnaryConsistent(const Feature& s, const Feature& m, const MatchingOptions& o) {
  if (s.type != m.type) return false;
  if (s.type == FeatureType::kCorner) {
    const double slack = PositionSlack(m.Range(), o.poserr);
    // Unary bounds 1 and 2.
    if (AngleDiff(s.Azimuth(), m.Azimuth()) > o.angerr + slack) return false;
    if (std::abs(s.Range() - m.Range()) > o.poserr) return false;
    // Unary properties 1 and 2. An occlusion corner's ray arm turns with the viewpoint.
    const double view = (s.occlusion || m.occlusion) ? slack : 0.0;
    if (std::abs(s.concave_angle - m.concave_angle) > o.concerr + view) return false;
    if (AngleDiff(s.bisector, m.bisector) > o.angerr + 0.5 * view) return false;
    return true;
  }
  // Unary bound 3: angular extents overlap, allowing the rotation.
  const double s0 = Bearing(s.start), s1 = Bearing(s.end);
  const double m0 = Bearing(m.start), m1 = Bearing(m.end);
  const double s_half = 0.5 * std::abs(NormalizeAngle(s1 - s0));
  const double m_half = 0.5 * std::abs(NormalizeAngle(m1 - m0));
  const double s_mid = s0 + NormalizeAngle(s1 - s0) * 0.5;
  const double m_mid = m0 + NormalizeAngle(m1 - m0) * 0.5;
  const double nearest = std::min({m.start.norm(), m.end.norm(), std::max(m.distance, 1e-3)});
  const double slack = PositionSlack(std::max(nearest, m.distance), o.poserr);
  if (AngleDiff(s_mid, m_mid) > s_half + m_half + o.angerr + slack) return false;
  // Unary properties 3 and 4.
  if (AngleDiff(s.orientation, m.orientation) > o.angerr) return false;
  if (std::abs(s.distance - m.distance) > o.poserr + o.disterr) return false;
  if (s.length > m.length + o.disterr) return false;
  return true;
}

bool BinaryConsistent(const Feature& s1, const Feature& m1, const Feature& s2, const Feature& m2,
                      const MatchingOptions& o) {
  const bool c1 = s1.type == FeatureType::kCorner, c2 = s2.type == FeatureType::kCorner;
  if (c1 && c2) {
    return std::abs((s1.position - s2.position).norm() - (m1.position - m2.position).norm()) <=
           o.bindisterr;
  }
  if (!c1 && !c2) {
    const double ds = NormalizeAngle(s1.orientation - s2.orientation);
    const double dm = NormalizeAngle(m1.orientation - m2.orientation);
    if (AngleDiff(ds, dm) > o.binangerr) return false;
    // Parallel lines: their separation is independent of the pose, as long as the
    // perpendiculars keep their sense (they point away from the sensor on both sides).
    if (std::abs(ds) < o.binangerr || std::abs(std::abs(ds) - kPi) < o.binangerr) {
      const double sep_s = std::abs(ds) < o.binangerr ? s1.distance - s2.distance
                                                      : s1.distance + s2.distance;
      const double sep_m = std::abs(ds) < o.binangerr ? m1.distance - m2.distance
                                                      : m1.distance + m2.distance;
      if (std::abs(sep_s - sep_m) > o.bindisterr) return false;
    }
    return true;
  }
  // A line and a corner: same signed distance of the corner from the line.
  const Feature& ls = c1 ? s2 : s1;
  const Feature& lm = c1 ? m2 : m1;
  const Feature& cs = c1 ? s1 : s2;
  const Feature& cm = c1 ? m1 : m2;
  return std::abs(ls.SignedDistance(cs.position) - lm.SignedDistance(cm.position)) <= o.bindisterr;
}

FeatureMatchResult MatchFeatures(const std::vector<Feature>& sensed, const std::vector<Feature>& model,
                                 const MatchingOptions& o) {
  FeatureMatchResult result;
  Search s{sensed, model, o, {}, {}, {}, {}, {}, {}};
  for (int i = 0; i < static_cast<int>(sensed.size()); ++i) {
    for (int j = 0; j < static_cast<int>(model.size()); ++j) {
      if (UnaryConsistent(sensed[static_cast<size_t>(i)], model[static_cast<size_t>(j)], o)) {
        s.pairs.push_back({i, j});
      }
    }
  }
  const int k = static_cast<int>(s.pairs.size());
  result.candidate_pairs = k;
  if (k == 0) return result;
  s.compatible.assign(static_cast<size_t>(k), std::vector<char>(static_cast<size_t>(k), 0));
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      const FeaturePair& p = s.pairs[static_cast<size_t>(a)];
      const FeaturePair& q = s.pairs[static_cast<size_t>(b)];
      if (p.sensed == q.sensed || p.model == q.model) continue;
      const bool ok = BinaryConsistent(sensed[static_cast<size_t>(p.sensed)], model[static_cast<size_t>(p.model)],
                                       sensed[static_cast<size_t>(q.sensed)], model[static_cast<size_t>(q.model)], o);
      s.compatible[static_cast<size_t>(a)][static_cast<size_t>(b)] = ok;
      s.compatible[static_cast<size_t>(b)][static_cast<size_t>(a)] = ok;
    }
  }
  // Longest chains of pairwise-consistent pairs in sensed order, out of and into each pair
  // (model order relaxed): upper bounds on any consistent set through the pair.
  s.out_len.assign(static_cast<size_t>(k), 1);
  s.in_len.assign(static_cast<size_t>(k), 1);
  for (int a = k - 1; a >= 0; --a) {
    for (int b = a + 1; b < k; ++b) {
      if (s.pairs[static_cast<size_t>(b)].sensed > s.pairs[static_cast<size_t>(a)].sensed &&
          s.compatible[static_cast<size_t>(a)][static_cast<size_t>(b)]) {
        s.out_len[static_cast<size_t>(a)] = std::max(s.out_len[static_cast<size_t>(a)], 1 + s.out_len[static_cast<size_t>(b)]);
      }
    }
  }
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < a; ++b) {
      if (s.pairs[static_cast<size_t>(b)].sensed < s.pairs[static_cast<size_t>(a)].sensed &&
          s.compatible[static_cast<size_t>(a)][static_cast<size_t>(b)]) {
        s.in_len[static_cast<size_t>(a)] = std::max(s.in_len[static_cast<size_t>(a)], 1 + s.in_len[static_cast<size_t>(b)]);
      }
    }
  }
  // Start from the pairs with the longest chains through them: good sets early make the
  // bounds bite.
  std::vector<int> starts(static_cast<size_t>(k));
  for (int a = 0; a < k; ++a) starts[static_cast<size_t>(a)] = a;
  std::stable_sort(starts.begin(), starts.end(), [&](int a, int b) {
    return s.in_len[static_cast<size_t>(a)] + s.out_len[static_cast<size_t>(a)] >
           s.in_len[static_cast<size_t>(b)] + s.out_len[static_cast<size_t>(b)];
  });
  for (int a : starts) {
    if (s.in_len[static_cast<size_t>(a)] + s.out_len[static_cast<size_t>(a)] - 1 <
        static_cast<int>(s.best.size())) {
      continue;
    }
    if (s.out_len[static_cast<size_t>(a)] < static_cast<int>(s.best.size())) continue;
    if (s.nodes >= o.max_search_nodes) {
      s.complete = false;
      break;
    }
    ++s.nodes;
    s.current = {a};
    s.Extend(a + 1);
  }
  std::sort(s.best.begin(), s.best.end());
  for (int i : s.best) result.pairs.push_back(s.pairs[static_cast<size_t>(i)]);
  result.search_nodes = s.nodes;
  result.search_complete = s.complete;
  return result;
}

void DeclareOptions(OptionScope scope, MatchingOptions& o) {
  scope.AddDouble("angerr", &o.angerr, "rad", "bound on the initial heading error (2.1.5; thesis 5 deg)", 0.0, 1.5);
  scope.AddDouble("poserr", &o.poserr, "m", "bound on the initial position error (2.1.5; thesis 1 m)", 0.0, 100.0);
  scope.AddDouble("concerr", &o.concerr, "rad", "tolerance on concave angles (thesis 10 deg)", 0.0, 3.0);
  scope.AddDouble("disterr", &o.disterr, "m", "tolerance on line distances beyond poserr (thesis 0.5 m)", 0.0,
                  100.0);
  scope.AddDouble("bindisterr", &o.bindisterr, "m", "tolerance of the binary distance constraints (thesis 0.5 m)",
                  0.0, 100.0);
  scope.AddDouble("binangerr", &o.binangerr, "rad", "tolerance of the binary angle constraints (thesis 5 deg)", 0.0,
                  3.0);
  scope.AddInt("max_search_nodes", &o.max_search_nodes,
               "bound on the nodes of the depth-first search, a time guard: a search cut short says so "
               "(search_complete false) (200000)",
               1, 1000000000);
}

}  // namespace minenav
