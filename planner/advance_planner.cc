#include "planner/advance_planner.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "common/angle.h"
#include "common/config.h"
#include "planner/contour_free_space.h"

namespace minenav {
namespace {

// The footprint's extent in the vehicle frame.
struct BodyExtent {
  double x_min = 0.0, x_max = 0.0;  // m along the heading
  double half_width = 0.0;          // m, the largest |y|
};

BodyExtent ExtentOf(const Footprint& footprint) {
  BodyExtent e;
  e.x_min = e.x_max = footprint.vertices.front().x();
  for (const Eigen::Vector2d& p : footprint.vertices) {
    e.x_min = std::min(e.x_min, p.x());
    e.x_max = std::max(e.x_max, p.x());
    e.half_width = std::max(e.half_width, std::abs(p.y()));
  }
  return e;
}

// One cut across the face: the lateral position of the vehicle's centre (face frame y) and
// the new width it takes out.
struct CutSlot {
  double y = 0.0;
  double width = 0.0;
};

Task MakeTask(TaskKind kind, const Pose2& target, Appendages appendages, std::string description) {
  Task t;
  t.kind = kind;
  t.target = target;
  t.appendages = appendages;
  t.description = std::move(description);
  return t;
}

}  // namespace

std::string ValidateOptions(const AdvanceOptions& o) {
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(o.reach)) return "reach must be > 0";
  if (!positive(o.drum_width)) return "drum_width must be > 0";
  if (!std::isfinite(o.standoff) || o.standoff < 0.0) return "standoff must be >= 0";
  if (!std::isfinite(o.side_margin) || o.side_margin < 0.0) return "side_margin must be >= 0";
  if (!std::isfinite(o.approach_length) || o.approach_length < 0.0) return "approach_length must be >= 0";
  if (o.box_cut_side != "right" && o.box_cut_side != "left") return "box_cut_side must be right or left";
  if (!positive(o.bolter_gap)) return "bolter_gap must be > 0";
  if (!positive(o.max_depth)) return "max_depth must be > 0";
  if (o.max_slab_cuts < 1) return "max_slab_cuts must be at least 1";
  if (o.maneuver_expansions < 1) return "maneuver_expansions must be at least 1";
  return ValidateOptions(o.entry);
}

void DeclareOptions(OptionScope s, AdvanceOptions& o) {
  s.AddDouble("reach", &o.reach, "m", "vehicle pose to the drum's front (the cutter's cutter.reach)", 0.1, 50.0);
  s.AddDouble("drum_width", &o.drum_width, "m", "the drum's width (the cutter's cutter.width)", 0.1, 20.0);
  s.AddDouble("standoff", &o.standoff, "m", "drum front to face where a cut starts (the cutter's cutter.standoff)", 0.0,
              5.0);
  s.AddDouble("side_margin", &o.side_margin, "m",
              "between the vehicle's side (or the drum's end) and a rib at a cut, beyond the clearance", 0.0, 5.0);
  s.AddDouble("approach_length", &o.approach_length, "m",
              "the ribs' nearest point counts this far behind the vehicle at a cut (it backs straight out)", 0.0,
              100.0);
  s.AddString("box_cut_side", &o.box_cut_side, "side of the entry (looking at the face) the box cut goes to",
              {"right", "left"});
  s.AddDouble("bolter_gap", &o.bolter_gap, "m",
              "drum front to the advanced face after backing out (room for the roof bolter)", 0.1, 200.0);
  s.AddDouble("max_depth", &o.max_depth, "m", "deeper advance requests are refused", 0.01, 100.0);
  s.AddInt("max_slab_cuts", &o.max_slab_cuts, "an entry that needs more slab cuts is refused", 1, 100);
  s.AddInt64("maneuver_expansions", &o.maneuver_expansions, "path planner expansions each maneuver check may take", 1,
             1'000'000'000);
  DeclareOptions(s.Nested("entry"), o.entry);
}

AdvanceResult PlanAdvance(const TaskMap& map_in, const Footprint& footprint_in, const AdvanceRequest& r,
                          const AdvanceOptions& o, const Se2PlannerOptions& planner_options,
                          const SearchLimits& limits, Se2PlannerCache* planners) {
  AdvanceResult result;
  TaskPlan& plan = result.plan;
  auto fail = [&](const std::string& why) {
    plan.status = PlanStatus::kFailed;
    plan.reason = why;
    plan.tasks.clear();
    return result;
  };
  if (const std::string e = ValidateOptions(o); !e.empty()) return fail("bad options: " + e);
  if (const std::string e = ValidateFootprint(footprint_in); !e.empty()) return fail("bad footprint: " + e);
  if (!std::isfinite(r.vehicle.x) || !std::isfinite(r.vehicle.y) || !std::isfinite(r.vehicle.theta))
    return fail("the vehicle pose is not finite");
  if (!std::isfinite(r.depth) || r.depth <= 0.0 || r.depth > o.max_depth)
    return fail("depth " + FixedNumber(r.depth) + " m is not in (0, " + FixedNumber(o.max_depth) + "] (max_depth)");
  if (!std::isfinite(r.clearance) || r.clearance < 0.0)
    return fail("clearance " + FixedNumber(r.clearance) + " m is not >= 0");
  const Footprint footprint = Normalized(footprint_in);
  const BodyExtent body = ExtentOf(footprint);
  // The vehicle stands where the ladar looked from: a frontier through it is no boundary.
  const TaskMap map = WithoutFrontiersAt(map_in, footprint, r.vehicle, r.clearance + planner_options.collision_step);

  EntryResult found = FindEntry(map, r.face_hint, r.direction, o.entry);
  if (!found.entry) return fail(found.reason);
  result.entry = found.entry;
  const EntryGeometry& e = *result.entry;

  // Squared to the face, the vehicle stands at face_angle to the ribs: what sticks out of it
  // (its outline and the drum's front corners) in the entry frame, about its centre.
  const double half_drum = 0.5 * o.drum_width;
  std::vector<Eigen::Vector2d> outline = footprint.vertices;
  outline.emplace_back(o.reach, half_drum);
  outline.emplace_back(o.reach, -half_drum);
  const Pose2 turned(0.0, 0.0, e.face_angle);
  double ex_min = 0.0, ex_max = 0.0, ey_lo = 0.0, ey_hi = 0.0;
  for (const Eigen::Vector2d& p : outline) {
    const Eigen::Vector2d q = turned * p;
    ex_min = std::min(ex_min, q.x()), ex_max = std::max(ex_max, q.x());
    ey_lo = std::min(ey_lo, q.y()), ey_hi = std::max(ey_hi, q.y());
  }
  const double cos_face = std::cos(e.face_angle), sin_face = std::sin(e.face_angle);
  // The face-frame centre of a vehicle whose centre is y_e across the entry and x_f along the
  // face's normal.
  auto centre_at = [&](double y_e, double x_f) {
    return e.EntryToFace(Eigen::Vector2d((x_f - sin_face * y_e) / cos_face, y_e));
  };
  const double gap = o.standoff + r.clearance;               // drum front to face at a MOVE's goal
  const double side_gap = r.clearance + o.side_margin;       // vehicle to rib at a cut
  const double half = std::max(body.half_width, half_drum);  // face frame: what meets the face across

  // The room between the ribs over the vehicle's length at a cut and approach_length behind it
  // (the ribs run along the entry's axis, so a vehicle at any heading keeps its distance to
  // them as it backs out along the axis: only the walls' wander counts).
  const double x_cut = -o.standoff - o.reach;  // face frame: the centre at a cut (face at 0)
  const double x_e_cut = x_cut / cos_face;
  const double x_lo = x_e_cut - r.clearance + ex_min - o.approach_length, x_hi = x_e_cut + ex_max;
  const double left = e.LeftLimit(x_lo, x_hi), right = e.RightLimit(x_lo, x_hi);
  const double room = (left - right) / cos_face;  // along the face
  const bool box_right = o.box_cut_side == "right";
  const double y_right = right - ey_lo + side_gap, y_left = left - ey_hi - side_gap;  // entry frame
  const double y_first = box_right ? y_right : y_left, y_last = box_right ? y_left : y_right;
  const double span = (y_left - y_right) / cos_face;  // along the face, between the first and last cut

  std::vector<CutSlot> slots;  // y: entry frame
  std::string layout;
  if (span <= 1e-6) {
    slots.push_back({0.5 * (left + right) - 0.5 * (ey_hi + ey_lo), std::min(o.drum_width, room)});
    layout = room < o.drum_width
                 ? "the entry (" + FixedNumber(room) + " m at the face) is narrower than the drum (" +
                       FixedNumber(o.drum_width) + " m): the box cut is the whole width, no slab cut"
                 : "the entry (" + FixedNumber(room) + " m at the face) leaves no room beside the box cut (" +
                       FixedNumber(o.drum_width) + " m, centred): no slab cut";
  } else {
    const int slabs = static_cast<int>(std::ceil(span / o.drum_width - 1e-9));
    if (slabs > o.max_slab_cuts)
      return fail("the entry (" + FixedNumber(room) + " m at the face) needs " + std::to_string(slabs) +
                  " slab cuts (at most " + std::to_string(o.max_slab_cuts) + ", max_slab_cuts)");
    for (int k = 0; k <= slabs; ++k)
      slots.push_back({y_first + (y_last - y_first) * k / slabs, k == 0 ? o.drum_width : span / slabs});
    layout = "box cut " + FixedNumber(o.drum_width) + " m on the " + o.box_cut_side + ", " + std::to_string(slabs) +
             " slab cut" + (slabs > 1 ? "s" : "") + " of " + FixedNumber(span / slabs) + " m";
  }

  // The tasks: MOVE + cut per slot, then BACK_OUT.
  double nearest_cut = 0.0;  // face frame x of the cuts' MOVE goals (the least)
  for (size_t k = 0; k < slots.size(); ++k) {
    const CutSlot& slot = slots[k];
    // The nearest face point in front of the vehicle, and beside it within the gap (a point just
    // past the drum's end may be nearer to its corner than the face ahead); found again for the
    // vehicle's place along the face once the face's distance is known.
    Eigen::Vector2d c = centre_at(slot.y, x_cut);
    for (int pass = 0; pass < 3; ++pass)
      c = centre_at(slot.y, e.FaceLimit(c.y() - half - gap, c.y() + half + gap) - o.standoff - o.reach);
    const Pose2 cut = e.FacePose(c.x(), c.y());
    const Pose2 move = e.FacePose(c.x() - r.clearance, c.y());
    nearest_cut = std::min(nearest_cut, c.x() - r.clearance);
    const bool box = k == 0;
    const std::string cut_name = box ? "box cut" : "slab cut " + std::to_string(k);
    Task m = MakeTask(TaskKind::kMove, move, Appendages::kStowed,
                      (box ? "move into position for the box cut" : "reposition for " + cut_name) +
                          ": squared to the face, drum " + FixedNumber(gap) + " m from it, " +
                          FixedNumber(slot.y + ey_lo - right) + " m from the right rib");
    m.clearance = r.clearance;
    m.allow_reverse = true;
    plan.tasks.push_back(std::move(m));
    Task t = MakeTask(box ? TaskKind::kBoxCut : TaskKind::kSlabCut, cut, Appendages::kCutting,
                      cut_name + ": " + FixedNumber(r.depth) + " m deep, " + FixedNumber(slot.width) + " m wide");
    t.depth = r.depth;
    t.width = slot.width;
    t.face = Segment(e.FacePoint(0.0, c.y() - half_drum), e.FacePoint(0.0, c.y() + half_drum));
    plan.tasks.push_back(std::move(t));
  }
  // Back out: back out of the last cut along the entry's axis (straight back when the face is
  // square; squared to the face still), the drum bolter_gap behind the advanced face.
  const double x_back = r.depth - o.bolter_gap - o.reach;
  if (x_back >= nearest_cut)
    return fail("bolter_gap " + FixedNumber(o.bolter_gap) + " m does not take the vehicle back from the cuts (depth " +
                FixedNumber(r.depth) + " m)");
  const Eigen::Vector2d b = centre_at(slots.back().y, x_back);
  Task back = MakeTask(TaskKind::kBackOut, e.FacePose(b.x(), b.y()), Appendages::kStowed,
                       "back out for the roof bolter: drum " + FixedNumber(o.bolter_gap) + " m from the advanced face");
  back.clearance = r.clearance;
  back.allow_reverse = true;
  plan.tasks.push_back(std::move(back));
  for (size_t k = 0; k < plan.tasks.size(); ++k) {
    plan.tasks[k].id = static_cast<int64_t>(k) + 1;
    plan.tasks[k].depends_on = static_cast<int64_t>(k);  // the one before (0: none)
  }
  plan.tasks.front().depends_on = -1;

  // Every driving goal: known free space, then the path planner from where the task before
  // leaves the vehicle (a cut leaves it where its MOVE put it: it trams straight back out).
  Se2PlannerOptions po = planner_options;
  po.clearance = r.clearance;
  const std::vector<Segment> walls = map.Boundary();
  const std::shared_ptr<const Se2Planner> planner_kept = PlannerFor(planners, walls, footprint, po);
  const Se2Planner& planner = *planner_kept;
  if (!planner.setup_error().empty()) return fail("path planner: " + planner.setup_error());
  std::unique_ptr<KnownFreeSpace> known;
  if (map.oriented) known = std::make_unique<KnownFreeSpace>(map.AsFreeSpace());
  // A vehicle within the clearance of a wall (it stopped short where the map grew around it)
  // leaves with the clearance it has: its first maneuver is checked as the path planner plans
  // it (never in contact with the map); the others keep the clearance.
  std::shared_ptr<const Se2Planner> leaving;
  if (!planner.PoseFree(r.vehicle))
    if (const std::optional<Se2PlannerOptions> leaving_options = planner.LeavingOptions(r.vehicle)) {
      leaving = PlannerFor(planners, walls, footprint, *leaving_options);
      result.leaving_clearance = leaving_options->clearance;
    }
  SearchLimits leg_limits = limits;
  leg_limits.max_expansions = std::min(limits.max_expansions, o.maneuver_expansions);
  Pose2 from = r.vehicle;
  std::ostringstream lengths;
  for (size_t k = 0; k < plan.tasks.size(); ++k) {
    const Task& t = plan.tasks[k];
    if (t.kind != TaskKind::kMove && t.kind != TaskKind::kBackOut) continue;
    const std::string name = t.description.substr(0, t.description.find(':'));
    if (known && !known->Contains(t.target.translation()))
      return fail(name + ": goal " + PoseText(t.target) + " is not in the known free space");
    const Se2Planner& leg_planner = leaving && result.maneuvers.empty() ? *leaving : planner;
    ManeuverCheck check{k, from, t.target, leg_planner.Plan(from, t.target, leg_limits)};
    const bool ok = check.result.status == SearchStatus::kFound;
    result.maneuvers.push_back(check);
    if (!ok)
      return fail(name + ": goal " + PoseText(t.target) + " is not reachable from " + PoseText(from) + ": " +
                  ToString(check.result.status) + ": " + check.result.reason);
    lengths << (lengths.tellp() > 0 ? " + " : "") << FixedNumber(check.result.path.Length(), 1);
    from = t.target;
  }

  plan.status = PlanStatus::kOk;
  plan.reason = "advance the " + FixedNumber(e.width) + " m entry " + FixedNumber(r.depth) + " m: " + layout +
                ", back out to " + FixedNumber(o.bolter_gap) + " m from the new face; face " +
                FixedNumber(RadToDeg(std::abs(e.face_angle)), 1) + " deg off square; " +
                std::to_string(result.maneuvers.size()) + " maneuvers checked (" + lengths.str() + " m)";
  if (leaving)
    plan.reason += " (the vehicle stood within " + FixedNumber(r.clearance) + " m of a wall: its first maneuver keeps " +
                   FixedNumber(*result.leaving_clearance) + " m)";
  return result;
}

}  // namespace minenav
