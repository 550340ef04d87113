// The contour mapper on the public CARMEN logs (issue #7; shared/datasets/SOURCES.md):
// Intel, Freiburg 079 and MIT CSAIL scored with the relation metric of Kuemmerle et al.
// 2009 (evaluation/relations.h) next to Cartographer's published figures (Hess et al., ICRA
// 2016, Table II), with raw odometry and iconic scan-to-scan matching (thesis 3.3 with the
// previous scan as the map) as baselines; the Freiburg hospital log (no relations) is mapped
// for its time and picture. Every log runs with the same options, the preset
// mapper/presets/carmen.conf (loaded as contour_mapper --preset carmen loads it): each scan
// is tracked against the contour map, scans are inserted at a spacing, and an optional
// final concurrent refinement (4.7) runs at the end.
//
//   mapper_carmen_bench [--datasets DIR] [--only intel,fr079,mit-csail,fr-clinic]
//                       [--max-scans N] [--svg-dir DIR] [--json-out FILE]
//                       [--final-refine-rounds N] [--baselines true]
//
// Wall-clock time is what a robot would wait; the machine is shared (2 cores), so CPU time of
// the process is printed too. Peak memory is the process's high-water mark (VmHWM), reset
// before each log where the kernel allows it.

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "common/config.h"
#include "common/file_io.h"
#include "dataset_readers/carmen_log.h"
#include "evaluation/relations.h"
#include "render/svg_render.h"
#include "mapper/mapper_presets.h"
#include "mapper/mapping_session.h"
#include "pose_estimator/iconic/iconic_estimator.h"

#ifndef MINENAV_DATASETS_DIR
#define MINENAV_DATASETS_DIR "../shared/datasets"
#endif

namespace {

using minenav::Pose2;
using minenav::StampedPose;
namespace mapper = minenav::mapper;

struct Dataset {
  std::string name;       // flag name
  std::string log;        // file in the datasets folder
  std::string relations;  // "" = none
  // Cartographer, Hess et al. 2016 Table II: abs. translational error m (mean, std),
  // abs. rotational error deg (mean, std). Negative = not published.
  double carto_t = -1, carto_t_std = -1, carto_r = -1, carto_r_std = -1;
};

const std::vector<Dataset>& Datasets() {
  static const std::vector<Dataset> kAll = {
      {"intel", "intel.clf.bz2", "intel.relations.txt", 0.0229, 0.0239, 0.453, 1.335},
      {"fr079", "fr079.clf.bz2", "fr079.relations.txt", 0.0452, 0.0354, 0.538, 0.718},
      {"mit-csail", "mit-csail.clf.bz2", "mit-csail.relations.txt", 0.0319, 0.0363, 0.369, 0.365},
      {"fr-clinic", "fr-clinic_robotlaser.clf.bz2", ""},
  };
  return kAll;
}

double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Resets the peak resident set size (Linux >= 4.0: writing 5 to clear_refs); false if not allowed.
bool ResetPeakRss() {
  std::ofstream out("/proc/self/clear_refs");
  if (!out) return false;
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

// Peak resident set size in MiB: VmHWM, else getrusage's (never reset) maximum.
double PeakRssMiB() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      in >> kb;
      return kb / 1024.0;
    }
    std::getline(in, key);
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

nlohmann::json ScoreJson(const minenav::RelationScore& s) {
  return {{"ok", s.ok},
          {"reason", s.reason},
          {"relations", s.relations},
          {"n", s.n},
          {"skipped", s.skipped},
          {"odometry_corrected", s.odometry_corrected},
          {"trans_mean_m", s.translation.mean},
          {"trans_std_m", s.translation.std},
          {"trans2_mean_m2", s.translation_squared.mean},
          {"trans2_std_m2", s.translation_squared.std},
          {"rot_mean_deg", s.rotation.mean},
          {"rot_std_deg", s.rotation.std},
          {"rot2_mean_deg2", s.rotation_squared.mean},
          {"rot2_std_deg2", s.rotation_squared.std}};
}

// Iconic scan-to-scan: each scan matched to the previous scan's raw polylines (the first-scan
// estimator of 3.3 with the previous scan as its map), starting from the previous estimate
// moved by the odometry since it. An unconverged match keeps that prediction.
std::vector<StampedPose> IconicScanToScan(const std::vector<minenav::LadarScan>& scans,
                                          const std::vector<minenav::OdometryReading>& odometry, int* failures) {
  minenav::IconicEstimatorOptions o;
  o.mode = minenav::IconicMode::kFirstScan;
  o.match.initial_threshold = 0.5;  // the same start as the contour mapper's tracking
  o.match.min_threshold = 0.1;      // SICK range noise is ~1 cm; 0.3 m is the Cyclone's
  std::vector<StampedPose> out;
  out.reserve(scans.size());
  *failures = 0;
  for (size_t i = 0; i < scans.size(); ++i) {
    if (i == 0) {
      out.push_back({scans[0].utime, odometry[0].pose});
      continue;
    }
    const Pose2 initial = out.back().pose * minenav::Between(odometry[i - 1].pose, odometry[i].pose);
    minenav::IconicEstimator estimator(o);
    estimator.AddScan(scans[i - 1], out.back().pose);
    const minenav::IconicMatchResult r = estimator.AddScan(scans[i], initial);
    if (!r.converged) ++*failures;
    out.push_back({scans[i].utime, r.converged ? r.pose : initial});
  }
  return out;
}

struct ContourRun {
  std::vector<StampedPose> poses;
  int64_t inserted = 0, tracked = 0, refused = 0;
  int contours = 0, segments = 0;
  double contour_length = 0.0;
  double wall_s = 0.0, cpu_s = 0.0, refine_wall_s = 0.0;
  int refine_rounds = 0;
  std::string refine_reason;
};

ContourRun RunContourMapper(const minenav::CarmenLog& log, const mapper::MappingSessionOptions& options,
                            int final_refine_rounds, const std::string& svg_path, const std::string& title) {
  mapper::MappingSession session(options);
  ContourRun run;
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = ProcessCpuSeconds();
  for (size_t i = 0; i < log.scans.size(); ++i) {
    session.AddScan(log.scans[i], log.scan_odometry[i].pose);
    if (i % 200 == 0 || i + 1 == log.scans.size())
      std::fprintf(stderr, "\r  [%s] scan %zu/%zu, %lld inserted, %lld refused, %d contours, %.0f s   ", title.c_str(),
                   i + 1, log.scans.size(), static_cast<long long>(session.state().inserted),
                   static_cast<long long>(session.state().refused), session.map().NumContours(),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::fprintf(stderr, "\n");
  if (final_refine_rounds > 0) {
    const auto r0 = std::chrono::steady_clock::now();
    const mapper::ConcurrentRefinementResult r = session.Refine();
    run.refine_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
    run.refine_rounds = r.rounds;
    run.refine_reason = r.reason;
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_s = ProcessCpuSeconds() - cpu0;
  run.poses = session.Poses();
  run.inserted = session.state().inserted;
  run.tracked = session.state().tracked;
  run.refused = session.state().refused;
  run.contours = session.map().NumContours();
  minenav::SvgLineLayer contours{"contours", "#1f4e9c", 1.0, {}, {}};
  for (const auto& [id, c] : session.map().contours()) {
    run.segments += c.NumSegments();
    for (int k = 0; k < c.NumSegments(); ++k) run.contour_length += c.GetSegment(k).length();
    contours.polylines.push_back({c.points, c.closed});
  }
  if (!svg_path.empty()) {
    minenav::SvgScene scene;
    scene.title = "contour map: " + title;
    std::ostringstream note;
    note << log.scans.size() << " scans: " << run.inserted << " inserted, " << run.tracked << " tracked, "
         << run.refused << " refused; " << run.contours << " contours, " << static_cast<int>(run.contour_length)
         << " m";
    scene.notes.push_back(note.str());
    scene.lines.push_back(contours);
    minenav::SvgTrajectory trajectory{"estimated path", "#c0392b", 0.6, false, false, {}};
    for (const StampedPose& p : run.poses) trajectory.poses.push_back(p.pose);
    scene.trajectories.push_back(trajectory);
    minenav::WriteFileAtomically(svg_path, minenav::RenderSvg(scene));
  }
  return run;
}

std::string Fmt(const minenav::RelationScore& s) {
  char buf[96];
  if (!s.ok) return "-";
  std::snprintf(buf, sizeof buf, "%.4f ± %.4f m, %.3f ± %.3f°", s.translation.mean, s.translation.std,
                s.rotation.mean, s.rotation.std);
  return buf;
}

int Run(int argc, char** argv) {
  std::string datasets_dir = MINENAV_DATASETS_DIR, only = "intel,fr079,mit-csail,fr-clinic", svg_dir, json_out;
  const mapper::MapperRunOptions preset = mapper::MapperPresetOptions("carmen");
  int max_scans = 0, final_refine_rounds = preset.final_refinement_rounds;
  bool baselines = true;
  // Overrides of mapper/presets/carmen.conf for experiments (0 = keep the preset's value).
  double insert_translation = 0, insert_rotation = 0, final_threshold = 0, max_range = 0, nominal_segment = 0;
  double discontinuity_angle = -1, initial_threshold = 0, heading_search = -1, heading_margin = -1;
  int min_pieces = 0;
  minenav::ConfigSchema schema("mapper_carmen_bench",
                               "Contour mapper on the CARMEN logs, scored with the Kuemmerle 2009 relations.");
  schema.AddString("datasets", &datasets_dir, "folder with the .clf.bz2 logs and .relations.txt files");
  schema.AddString("only", &only, "comma-separated datasets: intel, fr079, mit-csail, fr-clinic");
  schema.AddInt("max_scans", &max_scans, "use only the first N scans of each log (0 = all)", 0, 10000000);
  schema.AddString("svg_dir", &svg_dir, "write <dataset>_contours.svg here (empty = no pictures)");
  schema.AddString("json_out", &json_out, "JSON report");
  std::string poses_dir;
  schema.AddString("poses_dir", &poses_dir,
                   "write <dataset>_poses.csv (utime,x,y,theta: the contour mapper's poses) here, e.g. for "
                   "`log_tool relations` (empty = none)");
  schema.AddInt("final_refine_rounds", &final_refine_rounds,
                "concurrent refinement rounds after the last scan (0 = none)", 0, 1000);
  schema.AddBool("baselines", &baselines, "also score raw odometry and iconic scan-to-scan matching");
  schema.AddDouble("insert_translation", &insert_translation, "m", "override: insert spacing (0 = preset)", 0, 100);
  schema.AddDouble("insert_rotation", &insert_rotation, "rad", "override: insert turn (0 = preset)", 0, 10);
  schema.AddDouble("final_threshold", &final_threshold, "m", "override: pose final_threshold (0 = preset)", 0, 10);
  schema.AddDouble("initial_threshold", &initial_threshold, "m", "override: pose initial_threshold (0 = preset)", 0,
                   10);
  schema.AddDouble("heading_search", &heading_search, "rad",
                   "override: pose heading_search_range (-1 = preset, 0 = off)", -1, 3.14);
  schema.AddDouble("heading_margin", &heading_margin, "1",
                   "override: pose heading_search_margin (-1 = preset)", -1, 10);
  schema.AddInt("min_pieces", &min_pieces, "override: pose min_pieces (0 = preset)", 0, 100000);
  schema.AddDouble("max_range", &max_range, "m", "override: preprocessing max_range (0 = preset)", 0, 100);
  schema.AddDouble("nominal_segment", &nominal_segment, "m", "override: expansion nominal_segment_length (0 = preset)",
                   0, 10);
  schema.AddDouble("discontinuity_angle", &discontinuity_angle, "rad",
                   "override: preprocessing discontinuity_angle (-1 = preset, 0 = off)", -1, 1.5);
  if (schema.Parse(argc, argv) == minenav::ParseOutcome::kExit) return 0;
  mapper::MappingSessionOptions options = preset.session;
  options.mapper.refinement.max_rounds = std::max(1, final_refine_rounds);
  if (insert_translation > 0) options.insert_min_translation = insert_translation;
  if (insert_rotation > 0) options.insert_min_rotation = insert_rotation;
  if (final_threshold > 0) options.mapper.pose.final_threshold = final_threshold;
  if (max_range > 0) options.mapper.preprocessing.max_range = max_range;
  if (initial_threshold > 0) options.mapper.pose.initial_threshold = initial_threshold;
  if (heading_search >= 0) options.mapper.pose.heading_search_range = heading_search;
  if (heading_margin >= 0) options.mapper.pose.heading_search_margin = heading_margin;
  if (min_pieces > 0) options.mapper.pose.min_pieces = min_pieces;
  if (nominal_segment > 0) options.mapper.expansion.nominal_segment_length = nominal_segment;
  if (discontinuity_angle >= 0) options.mapper.preprocessing.discontinuity_angle = discontinuity_angle;
  if (const std::string why = mapper::ValidateOptions(options); !why.empty()) throw minenav::UsageError(why);

  std::vector<const Dataset*> chosen;
  std::stringstream list(only);
  for (std::string name; std::getline(list, name, ',');) {
    const Dataset* found = nullptr;
    for (const Dataset& d : Datasets())
      if (d.name == name) found = &d;
    if (!found) throw minenav::UsageError("--only: unknown dataset '" + name + "' (intel, fr079, mit-csail, fr-clinic)");
    chosen.push_back(found);
  }

  nlohmann::json report = {{"bench", "mapper_carmen_bench"},
                           {"max_scans", max_scans},
                           {"insert_min_translation_m", options.insert_min_translation},
                           {"insert_min_rotation_rad", options.insert_min_rotation},
                           {"pose_final_threshold_m", options.mapper.pose.final_threshold},
                           {"pose_initial_threshold_m", options.mapper.pose.initial_threshold},
                           {"pose_heading_search_range_rad", options.mapper.pose.heading_search_range},
                           {"pose_heading_search_margin", options.mapper.pose.heading_search_margin},
                           {"pose_min_pieces", options.mapper.pose.min_pieces},
                           {"max_range_m", options.mapper.preprocessing.max_range},
                           {"nominal_segment_length_m", options.mapper.expansion.nominal_segment_length},
                           {"discontinuity_angle_rad", options.mapper.preprocessing.discontinuity_angle},
                           {"final_refine_rounds", final_refine_rounds},
                           {"datasets", nlohmann::json::array()}};
  struct Line {
    std::string dataset, method, score, time;
  };
  std::vector<Line> table;
  for (const Dataset* d : chosen) {
    const bool reset = ResetPeakRss();
    const auto read0 = std::chrono::steady_clock::now();
    minenav::CarmenLog log = minenav::ReadCarmenLog(datasets_dir + "/" + d->log);
    const double read_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - read0).count();
    if (max_scans > 0 && static_cast<int>(log.scans.size()) > max_scans) {
      log.scans.resize(static_cast<size_t>(max_scans));
      log.scan_odometry.resize(static_cast<size_t>(max_scans));
    }
    if (log.scans.empty()) throw minenav::InputError(d->log + ": no scans");
    int64_t t0 = log.scans.front().utime, t1 = t0;
    for (const auto& s : log.scans) {
      t0 = std::min(t0, s.utime);
      t1 = std::max(t1, s.utime);
    }
    const double duration = 1e-6 * static_cast<double>(t1 - t0);
    std::vector<StampedPose> odometry;  // for the metric's odometry correction
    for (const auto& o : log.odometry.empty() ? log.scan_odometry : log.odometry) odometry.push_back({o.utime, o.pose});
    std::vector<StampedPose> scan_odometry;
    for (const auto& o : log.scan_odometry) scan_odometry.push_back({o.utime, o.pose});
    std::vector<minenav::Relation> relations;
    if (!d->relations.empty()) {
      relations = minenav::LoadRelations(datasets_dir + "/" + d->relations);
      // A slice keeps only the relations inside it (the rest would be scored by odometry).
      if (max_scans > 0) {
        std::vector<minenav::Relation> inside;
        for (const auto& r : relations)
          if (std::min(r.utime1, r.utime2) >= t0 && std::max(r.utime1, r.utime2) <= t1) inside.push_back(r);
        relations = std::move(inside);
      }
    }
    std::fprintf(stderr, "%s: %zu scans, %.0f s of data, %zu relations (read in %.1f s)\n", d->name.c_str(),
                 log.scans.size(), duration, relations.size(), read_s);

    nlohmann::json dj = {{"name", d->name},
                         {"scans", log.scans.size()},
                         {"duration_s", duration},
                         {"relations", relations.size()}};
    if (d->carto_t >= 0)
      dj["cartographer"] = {{"trans_mean_m", d->carto_t},
                            {"trans_std_m", d->carto_t_std},
                            {"rot_mean_deg", d->carto_r},
                            {"rot_std_deg", d->carto_r_std}};
    char buf[160];
    if (!relations.empty() && baselines) {
      const minenav::RelationScore odo = minenav::ScoreRelations(relations, scan_odometry, odometry);
      dj["odometry"] = ScoreJson(odo);
      table.push_back({d->name, "raw odometry", Fmt(odo), ""});
      const double c0 = ProcessCpuSeconds();
      const auto w0 = std::chrono::steady_clock::now();
      int failures = 0;
      const std::vector<StampedPose> s2s = IconicScanToScan(log.scans, log.scan_odometry, &failures);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
      const double cpu = ProcessCpuSeconds() - c0;
      const minenav::RelationScore ic = minenav::ScoreRelations(relations, s2s, odometry);
      dj["iconic_scan_to_scan"] = ScoreJson(ic);
      dj["iconic_scan_to_scan"]["wall_s"] = wall;
      dj["iconic_scan_to_scan"]["cpu_s"] = cpu;
      dj["iconic_scan_to_scan"]["unconverged"] = failures;
      std::snprintf(buf, sizeof buf, "%.0f s wall (%.0f× real time), %d unconverged", wall, duration / wall, failures);
      table.push_back({d->name, "iconic scan-to-scan", Fmt(ic), buf});
    }
    const std::string svg = svg_dir.empty() ? "" : svg_dir + "/" + d->name + "_contours.svg";
    const ContourRun run = RunContourMapper(log, options, final_refine_rounds, svg, d->name);
    const double peak = PeakRssMiB();
    if (!poses_dir.empty()) minenav::SavePosesCsv(poses_dir + "/" + d->name + "_poses.csv", run.poses);
    nlohmann::json cj = {{"wall_s", run.wall_s},
                         {"cpu_s", run.cpu_s},
                         {"real_time_factor", duration / run.wall_s},
                         {"refine_wall_s", run.refine_wall_s},
                         {"refine_rounds", run.refine_rounds},
                         {"refine_reason", run.refine_reason},
                         {"peak_rss_mib", peak},
                         {"peak_rss_reset", reset},
                         {"inserted", run.inserted},
                         {"tracked", run.tracked},
                         {"refused", run.refused},
                         {"contours", run.contours},
                         {"segments", run.segments},
                         {"contour_length_m", run.contour_length},
                         {"svg", svg}};
    std::string score = "(no relations)";
    if (!relations.empty()) {
      const minenav::RelationScore cs = minenav::ScoreRelations(relations, run.poses, odometry);
      cj.update(ScoreJson(cs));
      score = Fmt(cs);
    }
    dj["contour_mapper"] = cj;
    std::snprintf(buf, sizeof buf, "%.0f s wall, %.0f s CPU (%.1f× real time), %.0f MiB, %lld/%lld/%lld ins/trk/ref",
                  run.wall_s, run.cpu_s, duration / run.wall_s, peak, static_cast<long long>(run.inserted),
                  static_cast<long long>(run.tracked), static_cast<long long>(run.refused));
    table.push_back({d->name, "contour mapper", score, buf});
    if (d->carto_t >= 0) {
      std::snprintf(buf, sizeof buf, "%.4f ± %.4f m, %.3f ± %.3f°", d->carto_t, d->carto_t_std, d->carto_r,
                    d->carto_r_std);
      table.push_back({d->name, "Cartographer (published)", buf, ""});
    }
    report["datasets"].push_back(dj);
  }

  std::printf("\n%-10s | %-26s | %-36s | %s\n", "dataset", "method", "abs. trans. error, abs. rot. error", "time");
  std::printf("%s\n", std::string(120, '-').c_str());
  for (const Line& l : table)
    std::printf("%-10s | %-26s | %-36s | %s\n", l.dataset.c_str(), l.method.c_str(), l.score.c_str(), l.time.c_str());
  minenav::bench::WriteJson(json_out, report);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc, argv);
  } catch (const minenav::UsageError& e) {
    std::fprintf(stderr, "mapper_carmen_bench: error: %s\n", e.what());
    return minenav::kExitUsage;
  } catch (const minenav::InputError& e) {
    std::fprintf(stderr, "mapper_carmen_bench: error: %s\n", e.what());
    return minenav::kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mapper_carmen_bench: failed: %s\n", e.what());
    return minenav::kExitRuntime;
  }
}
