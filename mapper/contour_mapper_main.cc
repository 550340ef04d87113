// contour_mapper (thesis chapter 4, CLUE) as a process of the fleet.
//
// Batch (--log IN.lcm --map-out MAP.json [--poses-out POSES.csv] [--svg-out MAP.svg]):
// reads the log's LADAR_SCAN and ODOMETRY in file order, as fast as it can, maps every
// scan, runs a final concurrent refinement (4.7) and writes the contour-map JSON, one pose
// per inserted or tracked scan and a picture. Tools outside the project call exactly this.
//
// Live (no --log): subscribes the same channels, maps each scan as it arrives, publishes a
// pose_estimate_t on POSE per scan (source "clue"; converged = false and the reason in
// status for a refused scan) and contour_map_t on CONTOUR_MAP whenever the map changed
// (zlib-compressed above --compress-above bytes), plus HEARTBEAT.
//
// Both modes run the same policy (mapper/mapping_session.h) on the same scans paired with
// the same odometry (common/node/scan_odometry_sync.h), so replaying a log through the live
// process gives the batch map. Live, a worker thread owns the session: the LCM thread only
// pairs scans with odometry and queues them, so mapping and periodic refinement never
// block message handling. The queue holds at most --worker-queue-capacity scans: a mapper
// slower than its scans drops the oldest waiting one (see Worker), counts it, answers it on
// POSE and says so in HEARTBEAT. Publications made by the worker go to an outbox that the
// LCM thread empties on a 10 ms timer (the bus and its counters are touched by one thread
// only).
//
// --checkpoint FILE saves the whole state every --checkpoint-every scans and at shutdown
// (SIGINT/SIGTERM, end of log), before the final refinement; a restart with the same FILE
// resumes from it. --load-map starts from a saved contour map; --save-map writes the map at
// every checkpoint and at shutdown. No output may name an input (--log, --load-map,
// --checkpoint, --config): refused with exit code 2 before anything is read.
//
// Stopping (SIGINT/SIGTERM; a second signal ends the process at once, common/node):
//   * batch: the run is cut short, so the map, poses and SVG go to MAP.partial,
//     POSES.partial and SVG.partial (never the final names), without the final refinement,
//     with one log line saying what was kept; exit code 130 (kExitInterrupted). Refinements
//     and loop closure under way stop within one step (NodeRuntime::StopSignalled is their
//     stop test).
//   * live: the worker finishes the scan under way (a refinement in it stops), the scans
//     still queued or waiting for odometry are not mapped (counted in one log line and
//     answered on POSE), the checkpoint is saved, then the final refinement runs unless
//     scans were left unmapped (a mapper that was behind does not start a long computation
//     when told to stop); exit code 0.

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <ctime>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

#include "common/config.h"
#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "common/node/cpu_time.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_odometry_sync.h"
#include "common/pose_estimate.h"
#include "render/svg_render.h"
#include "mapper/carmen_session_options.h"
#include "mapper/contour_map_io.h"
#include "mapper/map_checkpoint.h"
#include "mapper/mapping_session.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

struct ProcessOptions {
  std::string map_out;
  std::string poses_out;
  std::string svg_out;
  std::string preset = "survey";
  std::string checkpoint;
  // handled scans (inserted or tracked); 0 = only at shutdown. Every 10 is about 1 s of
  // 10 Hz scans: a crash (kill -9, power) loses at most that, and a checkpoint of a few MB
  // writes in a few hundredths of a second (mapper/README.md).
  int checkpoint_every = 10;
  std::string load_map;
  std::string save_map;
  std::string scan_channel = "LADAR_SCAN";
  std::string odometry_channel = "ODOMETRY";
  std::string pose_channel = "POSE";
  std::string map_channel = "CONTOUR_MAP";
  double max_odometry_gap = 1.0;  // s
  int final_refinement_rounds = 10;
  int compress_above = kContourMapCompressAbove;  // bytes
  // Scans; live, the most that wait for the worker (default 100: 10 s of 10 Hz scans, about
  // 2 MB of 2048-point scans); a full queue drops its oldest scan.
  int worker_queue_capacity = 100;
};

void Declare(ConfigSchema& s, ProcessOptions& p, mapper::MappingSessionOptions& so) {
  mapper::ContourMapperOptions& mo = so.mapper;
  s.AddString("map_out", &p.map_out, "contour-map JSON written at the end (required with --log)");
  s.AddString("poses_out", &p.poses_out, "poses CSV utime,x,y,theta written at the end, one row per inserted or tracked scan");
  s.AddString("svg_out", &p.svg_out, "SVG of the map and the trajectory written at the end");
  s.AddString("preset", &p.preset,
              "option set the other flags start from: survey (360-degree scans at stations, thesis 5.2) or\n"
              "carmen (180-degree SICK scans from a moving robot: the public CARMEN logs, imported with\n"
              "log_tool import-carmen; mapper/carmen_session_options.h says why each value)");
  s.AddString("checkpoint", &p.checkpoint, "checkpoint file: resumed from when it exists, saved at shutdown");
  s.AddInt("checkpoint_every", &p.checkpoint_every,
           "with --checkpoint, also save it every this many handled scans (0 = at shutdown only)", 0, 1000000);
  s.AddString("load_map", &p.load_map, "start from this contour-map JSON (localise against it, keep extending)");
  s.AddString("save_map", &p.save_map, "contour-map JSON written at every checkpoint and at shutdown");
  s.AddChannel("scan_channel", &p.scan_channel, "subscribes", "ladar_scan_t", "scans");
  s.AddChannel("odometry_channel", &p.odometry_channel, "subscribes", "odometry_t", "initial estimates");
  s.AddChannel("pose_channel", &p.pose_channel, "publishes", "pose_estimate_t", "one estimate per scan (source clue)");
  s.AddChannel("map_channel", &p.map_channel, "publishes", "contour_map_t", "the map whenever it changed");
  s.AddDouble("max_odometry_gap", &p.max_odometry_gap, "s",
              "farthest odometry reading from a scan's utime that may serve for it", 0.0, 3600.0);
  s.AddInt("final_refinement_rounds", &p.final_refinement_rounds,
           "concurrent refinement rounds at the end (0 = none); also bounds periodic refinement", 0, 1000);
  s.AddInt("compress_above", &p.compress_above, "CONTOUR_MAP travels zlib-compressed above this many bytes", 0,
           1 << 30);
  s.AddInt("worker_queue_capacity", &p.worker_queue_capacity,
           "live: scans that may wait for the mapper [scans]; when full, the oldest waiting scan is dropped (counted,\n"
           "logged, answered on POSE, HEARTBEAT WARN) so the mapper is never more than this many scans behind",
           1, 1000000);
  s.AddDouble("insert_min_translation", &so.insert_min_translation, "m",
              "insert a scan when the vehicle moved this far since the last inserted one; others are tracked "
              "(0 = off; both off = insert every scan)",
              0.0, 1000.0);
  s.AddDouble("insert_min_rotation", &so.insert_min_rotation, "rad",
              "insert a scan when the heading changed this much since the last inserted one (0 = off)", 0.0, 3.2);
  s.AddInt("refine_every_inserts", &so.refine_every_inserts,
           "concurrent refinement after every this many inserts (0 = only at the end)", 0, 1000000);
  s.AddDouble("max_correction_translation", &mo.max_correction_translation, "m",
              "refuse a scan whose estimate moves further than this from its initial pose", 0.01, 100.0);
  s.AddDouble("max_correction_rotation", &mo.max_correction_rotation, "rad",
              "refuse a scan whose estimate turns further than this from its initial pose", 0.001, 3.2);
  s.AddDouble("max_rms_distance", &mo.max_rms_distance, "m",
              "refuse a scan whose RMS distance to the matched contours stays above this", 0.001, 10.0);
  s.AddDouble("min_overlap_fraction", &mo.min_overlap_fraction, "1",
              "fraction of a scan's points that must match the map", 0.0, 1.0);
  // Changing world (thesis 4.8; mapper/README.md "Changing worlds").
  s.AddBool("splice_interior", &mo.expansion.splice_interior,
            "4.8.1: splice objects that appear beside a mapped wall into its contour (false = static expansion)");
  s.AddDouble("min_splice_length", &mo.expansion.min_splice_length, "m",
              "shorter unmatched runs beside a contour's interior are not spliced", 0.0, 100.0);
  s.AddBool("disappearance", &mo.disappearance.enabled,
            "4.8.2: remove contour parts the scan sees through (triangles of coverage)");
  s.AddDouble("beam_divergence", &mo.disappearance.beam_divergence, "rad",
              "full beam divergence widening each triangle of coverage (Typhoon 0.003, Cyclone 0.004)", 0.0, 0.1);
  s.AddDouble("min_view_angle", &mo.disappearance.min_view_angle, "rad",
              "beams meeting a contour more glancingly than this remove nothing from it", 0.0, 1.57);
  s.AddHelpEpilog(
      "Examples:\n"
      "  contour_mapper --log survey.lcm --map-out map.json --poses-out poses.csv --svg-out map.svg   (batch)\n"
      "  contour_mapper --checkpoint run.ckpt --checkpoint-every 10 --save-map map.json                 (live)\n"
      "Exit codes: 0 ok, 2 bad flag or input file (or an output naming an input), 3 runtime failure,\n"
      "130 batch run stopped by SIGINT/SIGTERM (what was done is in MAP.partial, POSES.partial, SVG.partial).\n"
      "A second SIGINT/SIGTERM ends the process at once (the checkpoint is saved before the final refinement).\n");
}

struct Publication {
  std::string channel;
  std::vector<uint8_t> bytes;
};

pose_estimate_t RefusedPose(const LadarScan& scan, const Pose2& pose, const std::string& status) {
  MatchResult refused;
  refused.pose = pose;
  refused.status = status;
  return ToLcm(MakePoseEstimate(refused, scan.utime, scan.scan_id, "clue", 0.0));
}

// The mapping session and what the process does with each result. One thread at a time:
// the worker while it runs, the main thread before it starts and after it joined.
class MapperCore {
 public:
  MapperCore(const ProcessOptions& p, mapper::MappingSession session) : p_(p), session_(std::move(session)) {}

  mapper::MappingSession& session() { return session_; }
  const std::vector<double>& handle_seconds() const { return handle_seconds_; }
  const std::vector<double>& handle_cpu_seconds() const { return handle_cpu_seconds_; }

  // Maps one scan; returns what to publish.
  std::vector<Publication> Handle(const SyncedScan& s) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu0 = ThreadCpuSeconds();
    std::vector<Publication> out;
    const mapper::ScanResult r = session_.AddScan(s.scan, *s.odometry);
    const PoseEstimate e = MakePoseEstimate(r, s.scan.utime, s.scan.scan_id, "clue", ThreadCpuSeconds() - cpu0);
    out.push_back({p_.pose_channel, EncodeMessage(ToLcm(e))});
    const auto& st = session_.state();
    if (r.accepted()) {
      MINENAV_LOG(kInfo) << "scan " << s.scan.scan_id << " at " << s.scan.utime << ": " << ToString(r.outcome)
                         << ", " << session_.map().NumContours() << " contours, " << st.inserted << " inserted "
                         << st.tracked << " tracked " << st.refused << " refused";
      status_ = {heartbeat_t::OK, ""};
    } else {
      MINENAV_LOG(kWarn) << "scan " << s.scan.scan_id << " at " << s.scan.utime << ": refused: " << r.status;
      status_ = {heartbeat_t::WARN, "last scan refused: " + r.status};
    }
    if (r.outcome == mapper::ScanOutcome::kInserted) out.push_back(MapMessage(s.scan.utime));
    if (!p_.checkpoint.empty() && p_.checkpoint_every > 0 && ++since_checkpoint_ >= p_.checkpoint_every) {
      SaveState();
      since_checkpoint_ = 0;
    }
    handle_cpu_seconds_.push_back(ThreadCpuSeconds() - cpu0);
    handle_seconds_.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return out;
  }

  Publication MapMessage(int64_t utime, int64_t extra_version = 0) {
    ContourMapMessage m;
    m.utime = utime;
    const auto& st = session_.state();
    // Every handled scan counts, so the version keeps increasing across a restart.
    m.version = st.inserted + st.tracked + st.refused + extra_version;
    m.num_scans = static_cast<int32_t>(session_.mapper().scans().size());
    for (const auto& [id, c] : session_.map().contours()) m.contours.push_back({id, c.closed, c.points});
    const contour_map_t msg = ContourMapToLcm(m, p_.compress_above);
    last_map_bytes_ = msg.getEncodedSize();
    return {p_.map_channel, EncodeMessage(msg)};
  }

  // Checkpoint and map file (atomic writes).
  void SaveState() {
    if (!p_.checkpoint.empty()) {
      const auto t0 = std::chrono::steady_clock::now();
      mapper::SaveCheckpoint(p_.checkpoint, session_);
      MINENAV_LOG(kInfo) << "checkpoint " << p_.checkpoint << ": " << session_.mapper().scans().size() << " scans, "
                         << std::filesystem::file_size(p_.checkpoint) << " bytes, "
                         << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s";
    }
    if (!p_.save_map.empty()) mapper::SaveContourMapJson(p_.save_map, session_.map());
  }

  std::pair<int8_t, std::string> status() const { return status_; }
  int last_map_bytes() const { return last_map_bytes_; }
  // Bytes of the current map as CONTOUR_MAP, plain and compressed (for the summary line).
  std::pair<int, int> MapSizes() {
    ContourMapMessage m;
    for (const auto& [id, c] : session_.map().contours()) m.contours.push_back({id, c.closed, c.points});
    return {ContourMapToLcm(m, 1 << 30).getEncodedSize(), ContourMapToLcm(m, 0).getEncodedSize()};
  }

 private:
  const ProcessOptions& p_;
  mapper::MappingSession session_;
  int since_checkpoint_ = 0;
  std::pair<int8_t, std::string> status_{heartbeat_t::OK, ""};
  int last_map_bytes_ = 0;
  std::vector<double> handle_seconds_, handle_cpu_seconds_;
};

// Live: the thread that owns the MapperCore while the process runs.
//
// Scans wait for it in a queue of at most `capacity` (issue 11: unbounded, 10 000 scans at
// 1 kHz took the RSS from 7 to 98 MB and left the map five minutes behind). A scan arriving
// at a full queue pushes out the OLDEST waiting scan rather than being refused itself:
//   * whoever waits for POSE wants the newest scans' poses; the oldest is the stalest, and
//     the delay between a scan and its pose stays at most capacity x handling time;
//   * mapping stays correct for the scans handled: each carries its own odometry, and the
//     session composes the odometry motion since the last scan it accepted
//     (mapping_session.h), so a skipped scan only lengthens that motion (odometry is good
//     over the seconds a queue spans); the insertion policy (distance since the last
//     inserted scan) inserts the next handled scan that is far enough on, so the map loses
//     detail, not consistency. Which waiting scan would be inserted is not known before the
//     session sees it, so no scan is preferred for being "only tracked".
class Worker {
 public:
  Worker(MapperCore& core, size_t capacity) : core_(core), capacity_(capacity), thread_([this] { Loop(); }) {}
  ~Worker() { Stop(); }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Queues a scan; returns the scan pushed out to make room (the oldest waiting), if any.
  std::optional<SyncedScan> Push(SyncedScan s) {
    std::optional<SyncedScan> dropped;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (queue_.size() >= capacity_) {
        dropped = std::move(queue_.front());
        queue_.pop_front();
      }
      queue_.push_back(std::move(s));
    }
    wake_.notify_one();
    return dropped;
  }
  // Publications made since the last call, and the latest heartbeat status.
  std::vector<Publication> TakeOutbox(std::pair<int8_t, std::string>* status) {
    std::lock_guard<std::mutex> lock(mutex_);
    *status = status_;
    return std::exchange(outbox_, {});
  }
  // Lets the scan under way finish, stops the thread and returns the scans still queued
  // (not mapped). Idempotent.
  std::deque<SyncedScan> Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(queue_, {});
  }

 private:
  void Loop() {
    for (;;) {
      SyncedScan s;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        s = std::move(queue_.front());
        queue_.pop_front();
      }
      std::vector<Publication> out;
      try {
        out = core_.Handle(s);  // no lock held: the LCM thread keeps queuing
      } catch (const std::exception& e) {
        // A failure inside the mapper must not kill the process or lose later scans.
        MINENAV_LOG(kError) << "scan " << s.scan.scan_id << ": mapper failed: " << e.what();
      }
      std::lock_guard<std::mutex> lock(mutex_);
      status_ = core_.status();
      for (Publication& p : out) outbox_.push_back(std::move(p));
    }
  }

  MapperCore& core_;
  const size_t capacity_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<SyncedScan> queue_;
  std::vector<Publication> outbox_;
  std::pair<int8_t, std::string> status_{heartbeat_t::OK, ""};
  bool stopping_ = false;
  std::thread thread_;  // last: starts after the members it uses exist
};

// Scans the live worker's full queue pushed out: counted, logged at most once a second,
// and shown in HEARTBEAT (WARN while drops are recent). LCM thread only.
class QueueDrops {
 public:
  using SteadyClock = std::chrono::steady_clock;
  static constexpr std::chrono::seconds kLogEvery{1};
  // HEARTBEAT stays WARN this long after the last drop.
  static constexpr std::chrono::seconds kWarnFor{10};

  explicit QueueDrops(int capacity) : capacity_(capacity) {}

  void Count(const LadarScan& dropped) {
    ++count_;
    const auto now = SteadyClock::now();
    last_drop_ = now;
    if (count_ == 1 || now - last_log_ >= kLogEvery) {
      MINENAV_LOG(kWarn) << "mapper behind: its queue of " << capacity_ << " scans is full, dropped the oldest (scan "
                         << dropped.scan_id << " at " << dropped.utime << "); " << count_ << " dropped so far";
      last_log_ = now;
    }
  }
  int64_t count() const { return count_; }
  std::string PoseStatus() const {
    return "not mapped: dropped, the mapper's queue of " + std::to_string(capacity_) + " scans was full";
  }
  // The heartbeat status given the worker's: WARN while drops are recent, the count always.
  std::pair<int8_t, std::string> Status(std::pair<int8_t, std::string> worker) const {
    if (count_ == 0) return worker;
    const std::string dropped = std::to_string(count_) + " scans dropped (mapper queue of " +
                                std::to_string(capacity_) + " full)";
    if (SteadyClock::now() - last_drop_ < kWarnFor)
      return {heartbeat_t::WARN, "mapper behind: " + dropped + (worker.second.empty() ? "" : "; " + worker.second)};
    return {worker.first, worker.second.empty() ? dropped + " so far" : worker.second + "; " + dropped + " so far"};
  }

 private:
  const int capacity_;
  int64_t count_ = 0;
  SteadyClock::time_point last_drop_{}, last_log_{};
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Writes --map-out, --poses-out and --svg-out, each under its name + `suffix` (".partial"
// for an interrupted run), and --save-map when complete (an interrupted run saved it with
// the checkpoint already). Returns the files written with what they hold, for the log line.
std::string WriteOutputs(const ProcessOptions& p, const mapper::MappingSession& session, const std::string& title,
                         const std::string& suffix) {
  const bool partial = !suffix.empty();
  const std::vector<StampedPose> poses = session.Poses();
  std::string written;
  auto note = [&](const std::string& path, const std::string& what) {
    written += (written.empty() ? "" : ", ") + path + (what.empty() ? "" : " (" + what + ")");
  };
  const std::string contours = std::to_string(session.map().NumContours()) + " contours";
  if (!p.map_out.empty()) {
    mapper::SaveContourMapJson(p.map_out + suffix, session.map());
    note(p.map_out + suffix, contours);
  }
  if (!p.save_map.empty() && !partial) mapper::SaveContourMapJson(p.save_map, session.map());
  if (!p.poses_out.empty()) {
    SavePosesCsv(p.poses_out + suffix, poses);
    note(p.poses_out + suffix, std::to_string(poses.size()) + " poses");
  }
  if (!p.svg_out.empty()) {
    SvgScene scene;
    scene.title = "contour map of " + title + (partial ? " (interrupted: partial)" : "");
    const auto& st = session.state();
    scene.notes.push_back(std::to_string(st.inserted) + " scans inserted, " + std::to_string(st.tracked) +
                          " tracked, " + std::to_string(st.refused) + " refused, " +
                          std::to_string(session.map().NumContours()) + " contours");
    SvgLineLayer contour_layer{"contours", "#1f4e9c", 1.6, {}, {}};
    for (const auto& [id, c] : session.map().contours()) contour_layer.polylines.push_back({c.points, c.closed});
    scene.lines.push_back(contour_layer);
    SvgTrajectory trajectory{"refined poses", "#c0392b", 1.5, false, true, {}};
    for (const auto& q : poses) trajectory.poses.push_back(q.pose);
    scene.trajectories.push_back(trajectory);
    WriteFileAtomically(p.svg_out + suffix, RenderSvg(scene));
    note(p.svg_out + suffix, "");
  }
  return written.empty() ? "no output file" : written;
}

// The value of `flag` on the command line ("--flag VALUE" or "--flag=VALUE"; the last one
// wins), `fallback` when absent.
// Issue 11, item 13: an output naming an input (--map-out equal to --log overwrote the
// log) is refused before anything is read. The checkpoint is read and written by design,
// so it is an input of the other outputs only; a .partial name counts as its output too.
void CheckOutputsAreNotInputs(const ProcessOptions& p, const NodeOptions& node, const std::string& config) {
  const std::vector<std::string> inputs = {node.log, p.load_map, config};
  std::vector<std::string> inputs_and_checkpoint = inputs;
  inputs_and_checkpoint.push_back(p.checkpoint);
  const std::pair<const char*, std::string> outputs[] = {
      {"--map-out", p.map_out}, {"--poses-out", p.poses_out}, {"--svg-out", p.svg_out},
      {"--save-map", p.save_map}, {"--log-out", node.log_out}};
  for (const auto& [what, path] : outputs) {
    if (path.empty()) continue;
    CheckOutputIsNotInput(what, path, inputs_and_checkpoint);
    CheckOutputIsNotInput(what, path + ".partial", inputs_and_checkpoint);
  }
  CheckOutputIsNotInput("--checkpoint", p.checkpoint, inputs);
}

int Main(int argc, char** argv) {
  ConfigSchema schema("contour_mapper",
                      "Contour mapper (thesis ch. 4, CLUE): LADAR_SCAN + ODOMETRY -> contour map (CONTOUR_MAP), "
                      "poses (POSE); batch over a log with --log.");
  NodeRuntime runtime("contour_mapper", schema);
  ProcessOptions p;
  mapper::MappingSessionOptions so;
  // The preset picks the defaults the other options then override, so it is read first,
  // from the command line or the config file (what --print-config shows is in force).
  p.preset = PeekOption(argc, argv, "preset").value_or("survey");
  if (p.preset == "carmen") {
    so = mapper::CarmenSessionOptions();
    p.final_refinement_rounds = 0;  // the CARMEN figures are tracking without a final refinement
    p.max_odometry_gap = 5.0;       // Intel's ODOM stream pauses up to 2.3 s while the robot stands
  } else if (p.preset != "survey") {
    throw UsageError("--preset must be survey or carmen, got '" + p.preset + "'");
  }
  Declare(schema, p, so);
  if (schema.Parse(argc, argv) == ParseOutcome::kExit) return 0;
  const bool batch = !runtime.options().log.empty();
  if (batch && p.map_out.empty()) throw UsageError("--map-out is required with --log");
  so.mapper.refinement.max_rounds = std::max(1, p.final_refinement_rounds);
  if (const std::string why = mapper::ValidateOptions(so); !why.empty()) throw UsageError(why);
  if (schema.WasSet("checkpoint_every") && p.checkpoint.empty())
    throw UsageError("--checkpoint-every needs --checkpoint FILE");
  CheckOutputsAreNotInputs(p, runtime.options(), PeekOption(argc, argv, "config").value_or(""));
  // Long computations (refinement, loop closure) stop within one step of a stop signal:
  // the live worker then finishes its scan quickly, and a batch run is cut short at once.
  so.mapper.refinement.should_stop = [] { return NodeRuntime::StopSignalled(); };

  // The starting state: a checkpoint to resume, a map to extend, or nothing.
  std::unique_ptr<MapperCore> core;
  if (!p.checkpoint.empty() && std::filesystem::exists(p.checkpoint)) {
    core = std::make_unique<MapperCore>(p, mapper::RestoreSession(so, mapper::LoadCheckpoint(p.checkpoint)));
    const auto& st = core->session().state();
    MINENAV_LOG(kInfo) << "resumed from " << p.checkpoint << ": " << core->session().mapper().scans().size()
                       << " scans, " << core->session().map().NumContours() << " contours, " << st.inserted
                       << " inserted " << st.tracked << " tracked " << st.refused << " refused";
    if (!p.load_map.empty()) MINENAV_LOG(kWarn) << "--load-map ignored: resuming from the checkpoint";
  } else if (!p.load_map.empty()) {
    core = std::make_unique<MapperCore>(
        p, mapper::MappingSession(so, mapper::LoadContourMapJson(p.load_map, so.mapper.grid_cell_size)));
    MINENAV_LOG(kInfo) << "map " << p.load_map << ": " << core->session().map().NumContours() << " contours";
  } else {
    core = std::make_unique<MapperCore>(p, mapper::MappingSession(so));
  }

  runtime.Start();
  Bus& bus = runtime.bus();
  ScanOdometrySync sync({.max_odometry_gap_us = std::llround(p.max_odometry_gap * 1e6)});
  std::unique_ptr<Worker> worker;
  if (!batch) worker = std::make_unique<Worker>(*core, static_cast<size_t>(p.worker_queue_capacity));
  QueueDrops queue_drops(p.worker_queue_capacity);
  int64_t no_odometry = 0, scans_seen = 0, not_mapped_at_stop = 0;
  bool kept_partial = false;  // batch: the outputs are FILE.partial, exit kExitInterrupted
  const auto start = std::chrono::steady_clock::now();

  auto publish_all = [&](std::vector<Publication> pubs) {
    for (const Publication& pub : pubs) bus.Publish(pub.channel, pub.bytes.data(), static_cast<int>(pub.bytes.size()));
  };
  auto dispatch = [&](bool at_shutdown) {
    for (SyncedScan& s : sync.TakeReady(at_shutdown)) {
      if (!s.odometry) {
        ++no_odometry;
        const std::string why = "no odometry within " + std::to_string(p.max_odometry_gap) + " s";
        MINENAV_LOG(kWarn) << "scan " << s.scan.scan_id << " at " << s.scan.utime << ": " << why << "; skipped";
        Publish(bus, p.pose_channel, RefusedPose(s.scan, Pose2(), why));
        runtime.SetStatus(heartbeat_t::WARN, "no odometry for a scan");
        continue;
      }
      if (worker) {
        if (const std::optional<SyncedScan> dropped = worker->Push(std::move(s))) {
          queue_drops.Count(dropped->scan);
          Publish(bus, p.pose_channel, RefusedPose(dropped->scan, Pose2(), queue_drops.PoseStatus()));
        }
        continue;
      }
      publish_all(core->Handle(s));
      const auto [state, message] = core->status();
      runtime.SetStatus(state, message);
      if (batch)
        std::fprintf(stderr, "\r[contour_mapper] scan %lld, %d contours, %.1f s   ", static_cast<long long>(scans_seen),
                     core->session().map().NumContours(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
  };

  Subscribe<odometry_t>(bus, p.odometry_channel, [&](const odometry_t& m) {
    if (!sync.AddOdometry(FromLcm(m))) MINENAV_LOG(kWarn) << p.odometry_channel << " time went back: history cleared";
    dispatch(false);
  });
  Subscribe<ladar_scan_t>(bus, p.scan_channel, [&](const ladar_scan_t& m) {
    LadarScan scan;
    std::string why;
    try {
      scan = FromLcm(m);
      why = ValidateScan(scan);
    } catch (const InputError& e) {
      why = e.what();
    }
    if (!why.empty()) {
      // Reported on the bus too, so whoever waits for this scan's pose learns why; the
      // throw counts it as a bad message and logs it (bus.h).
      scan.utime = m.utime;
      scan.scan_id = m.scan_id;
      Publish(bus, p.pose_channel, RefusedPose(scan, Pose2(), "invalid scan: " + why));
      throw InputError("invalid scan " + std::to_string(m.scan_id) + ": " + why);
    }
    ++scans_seen;
    if (!sync.AddScan(std::move(scan))) MINENAV_LOG(kWarn) << "scans waiting for odometry: dropped the oldest";
    dispatch(false);
  });
  if (worker) {
    runtime.AddTimer(0.01, [&](int64_t) {
      std::pair<int8_t, std::string> status;
      publish_all(worker->TakeOutbox(&status));
      const auto [state, message] = queue_drops.Status(status);
      runtime.SetStatus(state, message);
    });
  }

  runtime.OnShutdown([&] {
    if (worker) {
      // Only the scan under way is finished: draining a backlog took minutes (issue 11).
      std::deque<SyncedScan> not_mapped = worker->Stop();
      for (SyncedScan& s : sync.TakeReady(true)) not_mapped.push_back(std::move(s));  // waiting for odometry
      std::pair<int8_t, std::string> status;
      publish_all(worker->TakeOutbox(&status));
      for (const SyncedScan& s : not_mapped)
        Publish(bus, p.pose_channel, RefusedPose(s.scan, Pose2(), "not mapped: the mapper stopped"));
      not_mapped_at_stop = static_cast<int64_t>(not_mapped.size());
      LogLine(not_mapped.empty() ? LogLevel::kInfo : LogLevel::kWarn)
          << "stopping: " << not_mapped.size() << " queued scans not mapped";
    } else {
      dispatch(true);
    }
    if (batch) std::fprintf(stderr, "\n");
    // Batch: cut short by a signal, before the end of the log or after it (the final
    // refinement would be the long part), or by damage in the log (the runtime then exits 2).
    const bool interrupted = batch && (runtime.interrupted() || NodeRuntime::StopSignalled());
    mapper::MappingSession& session = core->session();
    const auto& st = session.state();
    MINENAV_LOG(kInfo) << scans_seen << " scans received: " << st.inserted << " inserted, " << st.tracked << " tracked, "
                       << st.refused << " refused, " << no_odometry << " without odometry"
                       << (worker ? ", " + std::to_string(queue_drops.count()) + " dropped (queue full), " +
                                        std::to_string(not_mapped_at_stop) + " not mapped at the stop"
                                  : "")
                       << "; median handling time " << Median(core->handle_seconds()) << " s wall, "
                       << Median(core->handle_cpu_seconds()) << " s CPU per scan; last CONTOUR_MAP "
                       << core->last_map_bytes() << " bytes (map " << core->MapSizes().first << " bytes plain, "
                       << core->MapSizes().second << " compressed)";
    if (batch && scans_seen == 0 && !interrupted)
      throw InputError(runtime.options().log + ": no " + p.scan_channel + " messages");
    core->SaveState();  // before the final refinement: a restart continues the same sequence
    const std::string title = batch ? runtime.options().log : "the live run";
    // What an interrupted batch run keeps, in one line.
    auto keep_partial = [&](const std::string& what) {
      kept_partial = true;
      if (session.mapper().scans().empty()) {
        MINENAV_LOG(kWarn) << what << " before any scan was inserted: nothing written";
        return;
      }
      const std::string written = WriteOutputs(p, session, title, ".partial");
      MINENAV_LOG(kWarn) << what << ": kept " << st.inserted << " inserted, " << st.tracked << " tracked and "
                         << st.refused << " refused of " << scans_seen
                         << " scans read, without the final refinement, in " << written;
    };
    if (interrupted) {
      if (!NodeRuntime::StopSignalled()) return keep_partial("stopped at damage in the log");
      return keep_partial(runtime.interrupted() ? "interrupted before the end of the log" : "interrupted after the log");
    }
    if (session.mapper().scans().empty()) {
      if (batch) throw std::runtime_error("no scan could be inserted");
      MINENAV_LOG(kWarn) << "no scan inserted: no map written";
      return;
    }
    if (p.final_refinement_rounds > 0 && not_mapped_at_stop > 0) {
      MINENAV_LOG(kWarn) << "final refinement skipped: the mapper was behind when it stopped";
    } else if (p.final_refinement_rounds > 0) {
      // Live, the stop signal has already come (it is how a live run ends): the refinement
      // runs to its end unless a second signal ends the process (the checkpoint is saved).
      const auto refined = batch ? session.Refine() : session.Refine(mapper::ShouldStop{});
      MINENAV_LOG(kInfo) << "final refinement: " << refined.rounds << " rounds, " << refined.reason;
      if (refined.stopped) return keep_partial("interrupted in the final refinement");
      publish_all({core->MapMessage(runtime.NowUtime(), 1)});
    }
    MINENAV_LOG(kInfo) << "wrote " << WriteOutputs(p, session, title, "");
  });
  const int code = runtime.Run();
  // A signal after the last event (in the final refinement) leaves the runtime's code 0;
  // damage in the log keeps its code (2).
  return kept_partial && code == 0 ? kExitInterrupted : code;
}

}  // namespace
}  // namespace minenav

int main(int argc, char** argv) {
  return minenav::RunNodeMain("contour_mapper", [&] { return minenav::Main(argc, argv); });
}
