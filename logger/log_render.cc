#include "logger/log_render.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/file_io.h"

namespace minenav {

namespace {

// Colours that stay distinct for the colour-blind (Okabe-Ito) and on white paper.
const char* const kTrackColours[] = {"#0072B2", "#009E73", "#CC79A7", "#56B4E9", "#E69F00"};

std::vector<Eigen::Vector2d> Strided(const LadarScan& scan, const Pose2& pose, int max_points) {
  std::vector<Eigen::Vector2d> all = ScanPointsInWorld(scan, pose);
  if (max_points <= 0 || static_cast<int>(scan.ranges.size()) <= max_points) return all;
  // Keep readings by index stride so the density stays even around the sensor.
  const size_t stride = (scan.ranges.size() + static_cast<size_t>(max_points) - 1) / static_cast<size_t>(max_points);
  std::vector<Eigen::Vector2d> out;
  const Pose2 world_T_sensor = pose * scan.sensor_offset;
  for (size_t i = 0; i < scan.ranges.size(); i += stride) {
    if (!scan.IsValid(i)) continue;
    const double r = scan.ranges[i], a = scan.Bearing(i);
    out.push_back(world_T_sensor * Eigen::Vector2d(r * std::cos(a), r * std::sin(a)));
  }
  return out;
}

}  // namespace

std::vector<SvgPolyline> ParseContoursJson(const std::string& text, const std::string& source_name) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source_name + ": not valid JSON (byte " + std::to_string(e.byte) + ")");
  }
  if (!doc.is_object() || !doc.contains("contours") || !doc["contours"].is_array())
    throw InputError(source_name + ": expected an object with an array \"contours\"");
  std::vector<SvgPolyline> out;
  const auto& contours = doc["contours"];
  for (size_t i = 0; i < contours.size(); ++i) {
    const std::string where = source_name + ": contours[" + std::to_string(i) + "]";
    const auto& c = contours[i];
    if (!c.is_object() || !c.contains("points") || !c["points"].is_array())
      throw InputError(where + " has no array \"points\"");
    SvgPolyline pl;
    if (c.contains("closed")) {
      if (!c["closed"].is_boolean()) throw InputError(where + ": \"closed\" is not true or false");
      pl.closed = c["closed"].get<bool>();
    }
    for (size_t k = 0; k < c["points"].size(); ++k) {
      const auto& p = c["points"][k];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw InputError(where + ".points[" + std::to_string(k) + "] is not [x, y]");
      const Eigen::Vector2d v(p[0].get<double>(), p[1].get<double>());
      if (!v.allFinite()) throw InputError(where + ".points[" + std::to_string(k) + "] is not finite");
      pl.points.push_back(v);
    }
    out.push_back(std::move(pl));
  }
  return out;
}

LogRenderResult BuildLogScene(const std::string& log_path, const LogRenderOptions& options) {
  LogRenderResult result;
  SvgScene& scene = result.scene;
  const RunLog run = ReadRunLog(log_path);

  for (size_t i = 0; i < options.world_paths.size(); ++i) {
    SvgLineLayer world;
    world.label = options.world_paths.size() > 1 ? "world " + std::to_string(i) : "world walls";
    world.color = i == 0 ? "#333333" : "#999999";
    world.width_px = 1.2;
    world.segments = LoadSegmentsJson(options.world_paths[i]);
    scene.lines.push_back(std::move(world));
  }
  if (!options.map_path.empty()) {
    const std::string text = ReadFile(options.map_path);
    SvgLineLayer map;
    map.color = "#6A3D9A";
    map.width_px = 1.5;
    nlohmann::json probe = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (probe.is_object() && probe.contains("contours")) {
      map.polylines = ParseContoursJson(text, options.map_path);
      map.label = "map contours (" + std::to_string(map.polylines.size()) + ")";
    } else {
      map.segments = ParseSegmentsJson(text, options.map_path);
      map.label = "map segments (" + std::to_string(map.segments.size()) + ")";
    }
    scene.lines.push_back(std::move(map));
  }

  const auto track = [&](const std::string& channel) -> const PoseTrack* {
    const auto it = run.tracks.find(channel);
    return it == run.tracks.end() ? nullptr : &it->second;
  };
  const PoseTrack* truth = track(options.truth_channel);
  const PoseTrack* odometry = track(options.odometry_channel);

  std::string at = options.scans_at;
  if (at == "auto") at = truth ? "truth" : odometry ? "odometry" : "none";
  const PoseTrack* scan_track = nullptr;
  if (at == "truth") scan_track = truth;
  else if (at == "odometry") scan_track = odometry;
  else if (at != "none") scan_track = track(at);
  if (at != "none" && !scan_track) {
    const std::string channel = at == "truth" ? options.truth_channel : at == "odometry" ? options.odometry_channel : at;
    throw InputError(log_path + ": --scans-at " + options.scans_at + ": no poses on channel " + channel);
  }

  const auto scans_it = run.scans.find(options.scan_channel);
  const std::vector<LadarScan> no_scans;
  const std::vector<LadarScan>& all_scans = scans_it == run.scans.end() ? no_scans : scans_it->second;
  // A long live log has thousands of scans: draw an evenly spaced subset, first and last
  // included, so the file stays small enough to open.
  std::vector<LadarScan> scans;
  if (options.max_scans > 0 && all_scans.size() > static_cast<size_t>(options.max_scans)) {
    const size_t n = all_scans.size(), m = static_cast<size_t>(options.max_scans);
    for (size_t j = 0; j < m; ++j) scans.push_back(all_scans[m == 1 ? 0 : j * (n - 1) / (m - 1)]);
  } else {
    scans = all_scans;
  }
  if (scan_track) {
    SvgPointLayer layer;
    layer.label = "scan points at " + scan_track->channel + " poses";
    layer.color = "#E66100";
    for (const auto& scan : scans) {
      const auto pose = PoseAt(scan_track->poses, scan.utime, options.max_pose_gap_us);
      if (!pose) {
        ++result.scans_without_pose;
        continue;
      }
      ++result.scans_drawn;
      for (const auto& p : Strided(scan, *pose, options.max_points_per_scan)) layer.points.push_back(p);
    }
    scene.points.push_back(std::move(layer));
  }
  if (options.scans_at_odometry && odometry && scan_track != odometry) {
    SvgPointLayer layer;
    layer.label = "scan points at " + odometry->channel + " poses";
    layer.color = "#C00000";
    layer.opacity = 0.35;
    for (const auto& scan : scans) {
      const auto pose = PoseAt(odometry->poses, scan.utime, options.max_pose_gap_us);
      if (!pose) continue;
      for (const auto& p : Strided(scan, *pose, options.max_points_per_scan)) layer.points.push_back(p);
    }
    scene.points.push_back(std::move(layer));
  }

  // Error links: truth to odometry at the same utime.
  if (truth && odometry) {
    SvgLinks links;
    links.label = "error " + odometry->channel + " vs " + truth->channel;
    links.color = "#C00000";
    for (const auto& o : odometry->poses) {
      const auto t = PoseAt(truth->poses, o.utime, options.max_pose_gap_us);
      if (t) links.links.emplace_back(t->translation(), o.pose.translation());
    }
    scene.links.push_back(std::move(links));
  }

  // Markers only when the poses are sparse (stations); a 100 Hz track gets a line.
  const auto markers_for = [](const PoseTrack& t) { return t.poses.size() <= 400; };
  if (odometry) {
    SvgTrajectory tr;
    tr.label = odometry->channel + " (" + std::to_string(odometry->poses.size()) + ")";
    tr.color = "#C00000";
    tr.dashed = true;
    tr.markers = markers_for(*odometry);
    for (const auto& p : odometry->poses) tr.poses.push_back(p.pose);
    scene.trajectories.push_back(std::move(tr));
  }
  size_t colour = 0;
  for (const auto& [channel, t] : run.tracks) {
    if (&t == truth || &t == odometry) continue;
    SvgTrajectory tr;
    tr.label = channel + " (" + std::to_string(t.poses.size()) + ")";
    tr.color = kTrackColours[colour++ % std::size(kTrackColours)];
    tr.markers = markers_for(t);
    for (const auto& p : t.poses) tr.poses.push_back(p.pose);
    scene.trajectories.push_back(std::move(tr));
  }
  if (truth) {
    SvgTrajectory tr;
    tr.label = truth->channel + " (" + std::to_string(truth->poses.size()) + ")";
    tr.color = "#000000";
    tr.width_px = 2.0;
    tr.markers = markers_for(*truth);
    for (const auto& p : truth->poses) tr.poses.push_back(p.pose);
    scene.trajectories.push_back(std::move(tr));
  }

  scene.title = options.title.empty() ? log_path : options.title;
  std::ostringstream note;
  note << all_scans.size() << " scans on " << options.scan_channel;
  if (scan_track) note << ", " << result.scans_drawn << " drawn at " << scan_track->channel << " poses";
  if (result.scans_without_pose) note << ", " << result.scans_without_pose << " without a pose";
  if (options.max_points_per_scan > 0) note << " (at most " << options.max_points_per_scan << " points each)";
  scene.notes.push_back(note.str());
  return result;
}

}  // namespace minenav
