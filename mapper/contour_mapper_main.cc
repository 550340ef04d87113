// contour_mapper, batch mode (thesis chapter 4): builds a contour map from a log's
// LADAR_SCAN with ODOMETRY as the initial estimates, the first scan fixed, then runs a
// final concurrent refinement (4.7) and writes the contour-map JSON, one refined pose per
// scan (poses CSV) and optionally an SVG.
//
// Initial estimate of each scan: the odometry motion since the previous accepted scan
// (odometry interpolated at each scan's utime) composed onto that scan's refined pose; the
// first scan is fixed at its odometry pose and defines the map frame. Using the odometry
// poses directly would carry the first scan's error as a frame offset that grows with
// distance from it (2 degrees is 0.7 m at 20 m), which the mapper must then undo.
//
// The live process (subscribing, CONTOUR_MAP publishing, checkpoints) is the next step of
// issue 5; this binary runs over logs only and says so when --log is missing.

#include <chrono>
#include <cstdio>
#include <deque>
#include <map>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "common/pose_at_time.h"
#include "logger/svg_render.h"
#include "mapper/contour_map_io.h"
#include "mapper/contour_mapper.h"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"

namespace minenav {
namespace {

struct BatchOptions {
  std::string log;
  std::string map_out;
  std::string poses_out;
  std::string svg_out;
  std::string scan_channel = "LADAR_SCAN";
  std::string odometry_channel = "ODOMETRY";
  double max_odometry_gap = 1.0;  // s
  int final_refinement_rounds = 10;
};

int Main(int argc, char** argv) {
  ConfigSchema schema("contour_mapper",
                      "Contour mapper (thesis ch. 4, CLUE), batch over a log: LADAR_SCAN + ODOMETRY -> "
                      "contour map, refined poses, picture.");
  BatchOptions o;
  mapper::ContourMapperOptions mo;
  schema.AddString("log", &o.log, "LCM log to map (required)");
  schema.AddString("map_out", &o.map_out, "contour-map JSON to write (required)");
  schema.AddString("poses_out", &o.poses_out, "refined poses CSV utime,x,y,theta, one row per accepted scan");
  schema.AddString("svg_out", &o.svg_out, "SVG of the map, the scans and the trajectory");
  schema.AddChannel("scan_channel", &o.scan_channel, "reads", "ladar_scan_t", "scans");
  schema.AddChannel("odometry_channel", &o.odometry_channel, "reads", "odometry_t", "initial estimates");
  schema.AddDouble("max_odometry_gap", &o.max_odometry_gap, "s",
                   "farthest odometry reading from a scan's utime that may serve for it", 0.0, 3600.0);
  schema.AddInt("final_refinement_rounds", &o.final_refinement_rounds,
                "concurrent refinement rounds at the end (0 = none)", 0, 1000);
  schema.AddDouble("max_correction_translation", &mo.max_correction_translation, "m",
                   "refuse a scan whose estimate moves further than this from its initial pose", 0.01, 100.0);
  schema.AddDouble("max_correction_rotation", &mo.max_correction_rotation, "rad",
                   "refuse a scan whose estimate turns further than this from its initial pose", 0.001, 3.2);
  schema.AddDouble("max_rms_distance", &mo.max_rms_distance, "m",
                   "refuse a scan whose RMS distance to the matched contours stays above this", 0.001, 10.0);
  schema.AddDouble("min_overlap_fraction", &mo.min_overlap_fraction, "1",
                   "fraction of a scan's points that must match the map", 0.0, 1.0);
  schema.AddHelpEpilog(
      "Example:\n"
      "  contour_mapper --log survey.lcm --map-out map.json --poses-out poses.csv --svg-out map.svg\n"
      "Exit codes: 0 ok, 2 bad flag or input file, 3 runtime failure.\n");
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  if (o.log.empty()) throw UsageError("--log is required (this version maps logs; see --help)");
  if (o.map_out.empty()) throw UsageError("--map-out is required");
  mo.refinement.max_rounds = std::max(1, o.final_refinement_rounds);
  const std::string why = mapper::ValidateOptions(mo);
  if (!why.empty()) throw UsageError(why);

  // Read every scan and odometry reading first: a log is ordered by receive time, and an
  // offline survey writes ODOMETRY next to its scan.
  std::vector<LadarScan> scans;
  std::deque<OdometryReading> odometry;
  int bad = 0;
  LogReader reader(o.log);
  while (const LogEvent* e = reader.NextInPlace()) {
    std::string error;
    try {
      if (e->channel == o.scan_channel) {
        ladar_scan_t m{};
        if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &m, &error))
          throw InputError(error);
        scans.push_back(FromLcm(m));
      } else if (e->channel == o.odometry_channel) {
        odometry_t m{};
        if (!DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &m, &error))
          throw InputError(error);
        odometry.push_back(FromLcm(m));
      }
    } catch (const InputError& err) {
      ++bad;
      MINENAV_LOG(kWarn) << "event " << e->eventnum << ": " << err.what() << "; skipped";
    }
  }
  std::stable_sort(odometry.begin(), odometry.end(),
                   [](const OdometryReading& a, const OdometryReading& b) { return a.utime < b.utime; });
  if (scans.empty()) throw InputError(o.log + ": no " + o.scan_channel + " messages");
  MINENAV_LOG(kInfo) << o.log << ": " << scans.size() << " scans, " << odometry.size() << " odometry readings, "
                     << bad << " bad messages";

  const int64_t max_gap_us = std::llround(o.max_odometry_gap * 1e6);
  mapper::ContourMapper mapper(mo);
  std::vector<StampedPose> poses;
  std::optional<std::pair<Pose2, Pose2>> last;  // (refined pose, odometry) of the last accepted scan
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < scans.size(); ++i) {
    const LadarScan& scan = scans[i];
    const std::optional<Pose2> odo = PoseAtTime(odometry, scan.utime, max_gap_us);
    if (!odo) {
      MINENAV_LOG(kWarn) << "scan " << scan.scan_id << ": no odometry within " << o.max_odometry_gap << " s; skipped";
      continue;
    }
    const Pose2 initial = last ? last->first * Between(last->second, *odo) : *odo;
    const mapper::InsertResult r = mapper.InsertScan(scan, initial);
    if (r.accepted) {
      last = std::make_pair(r.pose, *odo);
    } else {
      MINENAV_LOG(kWarn) << "scan " << scan.scan_id << " refused: " << r.reason;
    }
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "\r[contour_mapper] scan %zu/%zu, %zu contours, %.1f s   ", i + 1, scans.size(),
                 mapper.map().contours().size(), elapsed);
  }
  std::fprintf(stderr, "\n");
  if (mapper.scans().empty()) throw std::runtime_error("no scan could be inserted");
  if (o.final_refinement_rounds > 0) {
    const auto refined = mapper.Refine();
    MINENAV_LOG(kInfo) << "final refinement: " << refined.rounds << " rounds, " << refined.reason;
  }

  // Poses of the accepted scans, keyed by their scans' utimes.
  for (const mapper::MappedScan& s : mapper.scans()) poses.push_back({s.scan.utime, s.pose});
  mapper::SaveContourMapJson(o.map_out, mapper.map());
  if (!o.poses_out.empty()) SavePosesCsv(o.poses_out, poses);
  if (!o.svg_out.empty()) {
    SvgScene scene;
    scene.title = "contour map of " + o.log;
    scene.notes.push_back(std::to_string(mapper.scans().size()) + " of " + std::to_string(scans.size()) +
                          " scans inserted, " + std::to_string(mapper.map().contours().size()) + " contours");
    SvgLineLayer contours{"contours", "#1f4e9c", 1.6, {}, {}};
    for (const auto& [id, c] : mapper.map().contours()) contours.polylines.push_back({c.points, c.closed});
    scene.lines.push_back(contours);
    SvgTrajectory trajectory{"refined poses", "#c0392b", 1.5, false, true, {}};
    for (const auto& p : poses) trajectory.poses.push_back(p.pose);
    scene.trajectories.push_back(trajectory);
    WriteFileAtomically(o.svg_out, RenderSvg(scene));
  }
  MINENAV_LOG(kInfo) << "wrote " << o.map_out << " (" << mapper.map().contours().size() << " contours)"
                     << (o.poses_out.empty() ? "" : ", " + o.poses_out) << (o.svg_out.empty() ? "" : ", " + o.svg_out);
  return 0;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  minenav::SetLogProgramName("contour_mapper");
  try {
    return minenav::Main(argc, argv);
  } catch (const minenav::UsageError& e) {
    std::fprintf(stderr, "contour_mapper: error: %s\n", e.what());
    return minenav::kExitUsage;
  } catch (const minenav::InputError& e) {
    std::fprintf(stderr, "contour_mapper: error: %s\n", e.what());
    return minenav::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contour_mapper: failed: %s\n", e.what());
    return minenav::kExitRuntime;
  }
}
