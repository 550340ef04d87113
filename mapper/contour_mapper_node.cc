#include "mapper/contour_mapper_node.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <utility>
#include <vector>

#include "common/file_io.h"
#include "common/log.h"
#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/cpu_time.h"
#include "common/pose_estimate.h"
#include "mapper/contour_map_io.h"
#include "mapper/map_checkpoint.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "render/svg_render.h"

namespace minenav {

void DeclareOptions(OptionScope s, ContourMapperNodeOptions& o) {
  s.AddString("map_out", &o.map_out, "contour-map JSON written at the end (required with --log)");
  s.AddString("poses_out", &o.poses_out,
              "poses CSV utime,x,y,theta,status (inserted or tracked) written at the end, one row per inserted or tracked scan");
  s.AddString("svg_out", &o.svg_out, "SVG of the map and the trajectory written at the end");
  s.AddString("checkpoint", &o.checkpoint, "checkpoint file: resumed from when it exists, saved at shutdown");
  s.AddInt("checkpoint_every", &o.checkpoint_every,
           "with --checkpoint, also save it every this many handled scans (0 = at shutdown only); 10 is about "
           "1 s of 10 Hz scans: a crash loses at most that, and a few-MB checkpoint writes in hundredths of a "
           "second [scans]",
           0, 1000000);
  s.AddBool("checkpoint_inserts", &o.checkpoint_inserts,
            "live, with --checkpoint: also save it at every inserted scan, before its POSE goes out, so that a "
            "kill -9 loses no inserted scan (batch runs ignore it)");
  s.AddDouble("map_republish_period", &o.map_republish_period, "s",
              "live: CONTOUR_MAP sent again when unchanged this long, and at the start when resumed, so a process "
              "that restarts gets the map without waiting for the vehicle to move; 0 = only on a change",
              0.0, 3600.0);
  s.AddString("load_map", &o.load_map, "start from this contour-map JSON (localise against it, keep extending)");
  s.AddString("save_map", &o.save_map, "contour-map JSON written at every checkpoint and at shutdown");
  s.schema().AddChannel(s.Key("scan_channel"), &o.scan_channel, "subscribes", "ladar_scan_t", "scans");
  s.schema().AddChannel(s.Key("odometry_channel"), &o.odometry_channel, "subscribes", "odometry_t",
                        "initial estimates");
  s.schema().AddChannel(s.Key("pose_channel"), &o.pose_channel, "publishes", "pose_estimate_t",
                        "one estimate per scan (source clue)");
  s.schema().AddChannel(s.Key("map_channel"), &o.map_channel, "publishes", "contour_map_t",
                        "the map whenever it changed");
  s.AddInt("compress_above", &o.compress_above,
           "CONTOUR_MAP travels zlib-compressed above this many bytes (32 KB: a survey's map travels plain; "
           "float coordinates barely compress) [bytes]",
           0, 1 << 30);
  s.AddInt("worker_queue_capacity", &o.worker_queue_capacity,
           "live: scans that may wait for the mapper [scans]; when full, the oldest waiting scan is dropped (counted,\n"
           "logged, answered on POSE, HEARTBEAT WARN) so the mapper is never more than this many scans behind",
           1, 1000000);
  mapper::DeclareOptions(s, o.run);
  // The flat names of the process before its options were nested (scripts and tests use them).
  for (const auto& [alias, key] : std::initializer_list<std::pair<const char*, const char*>>{
           {"max_correction_translation", "mapper.max_correction_translation"},
           {"max_correction_rotation", "mapper.max_correction_rotation"},
           {"max_rms_distance", "mapper.max_rms_distance"},
           {"min_overlap_fraction", "mapper.min_overlap_fraction"},
           {"splice_interior", "mapper.expansion.splice_interior"},
           {"min_splice_length", "mapper.expansion.min_splice_length"},
           {"disappearance", "mapper.disappearance.enabled"},
           {"beam_divergence", "mapper.disappearance.beam_divergence"},
           {"min_view_angle", "mapper.disappearance.min_view_angle"}})
    s.AddAlias(alias, key);
}

void ValidateNodeOptions(const ContourMapperNodeOptions& o, const NodeOptions& node, const std::string& config) {
  if (!node.log.empty() && o.map_out.empty()) throw UsageError("--map-out is required with --log");
  if (const std::string why = mapper::ValidateOptions(o.run); !why.empty()) throw UsageError(why);
  // Issue 11, item 13: an output naming an input (--map-out equal to --log overwrote the
  // log) is refused before anything is read. The checkpoint is read and written by design,
  // so it is an input of the other outputs only; a .partial name counts as its output too.
  const std::vector<std::string> inputs = {node.log, o.load_map, config};
  std::vector<std::string> inputs_and_checkpoint = inputs;
  inputs_and_checkpoint.push_back(o.checkpoint);
  const std::pair<const char*, std::string> outputs[] = {{"--map-out", o.map_out},
                                                         {"--poses-out", o.poses_out},
                                                         {"--svg-out", o.svg_out},
                                                         {"--save-map", o.save_map},
                                                         {"--log-out", node.log_out}};
  for (const auto& [what, path] : outputs) {
    if (path.empty()) continue;
    CheckOutputIsNotInput(what, path, inputs_and_checkpoint);
    CheckOutputIsNotInput(what, path + ".partial", inputs_and_checkpoint);
  }
  CheckOutputIsNotInput("--checkpoint", o.checkpoint, inputs);
}

mapper::MappingSession OpenMappingSession(const ContourMapperNodeOptions& o) {
  mapper::MappingSessionOptions so = o.run.session;
  // Long computations (refinement, loop closure) stop within one step of a stop signal:
  // the live worker then finishes its scan quickly, and a batch run is cut short at once.
  so.mapper.refinement.should_stop = [] { return NodeRuntime::StopSignalled(); };
  if (!o.checkpoint.empty() && std::filesystem::exists(o.checkpoint)) {
    std::string warning;
    mapper::MappingSession session =
        mapper::RestoreSession(so, mapper::LoadCheckpointOrPrevious(o.checkpoint, &warning));
    if (!warning.empty()) MINENAV_LOG(kWarn) << warning;
    const auto& st = session.state();
    MINENAV_LOG(kInfo) << "resumed from " << o.checkpoint << ": " << session.mapper().scans().size() << " scans, "
                       << session.map().NumContours() << " contours, " << st.inserted << " inserted " << st.tracked
                       << " tracked " << st.refused << " refused";
    if (!o.load_map.empty()) MINENAV_LOG(kWarn) << "--load-map ignored: resuming from the checkpoint";
    return session;
  }
  if (!o.load_map.empty()) {
    mapper::MappingSession session(so, mapper::LoadContourMapJson(o.load_map, so.mapper.grid_cell_size));
    MINENAV_LOG(kInfo) << "map " << o.load_map << ": " << session.map().NumContours() << " contours";
    return session;
  }
  return mapper::MappingSession(so);
}

namespace {

struct Publication {
  std::string channel;
  std::vector<uint8_t> bytes;
};

using Status = std::pair<int8_t, std::string>;

// The answer to a scan that was not mapped (dropped from a full queue, left at a stop).
pose_estimate_t UnmappedPose(const LadarScan& scan, const std::string& status) {
  MatchResult unmapped;
  unmapped.status = status;
  return ToLcm(MakePoseEstimate(unmapped, scan.utime, scan.scan_id, "clue", 0.0));
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Writes --map-out, --poses-out and --svg-out, each under its name + `suffix` (".partial"
// for an interrupted run), and --save-map when complete (an interrupted run saved it with
// the checkpoint already). Returns the files written with what they hold, for the log line.
std::string WriteOutputs(const ContourMapperNodeOptions& p, const mapper::MappingSession& session,
                         const std::string& title, const std::string& suffix) {
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

}  // namespace

// What mapping one scan produced: the publications and the heartbeat status after it.
struct ContourMapperNode::Answer {
  std::vector<Publication> publications;
  Status status;
};

// The mapping session and what the node does with each result. One thread at a time: the
// worker while it runs, the node thread before it starts and after it stopped.
class ContourMapperNode::Core {
 public:
  Core(const ContourMapperNodeOptions& p, mapper::MappingSession session, bool live)
      : p_(p), session_(std::move(session)), live_(live) {}

  mapper::MappingSession& session() { return session_; }
  const std::vector<double>& handle_seconds() const { return handle_seconds_; }
  const std::vector<double>& handle_cpu_seconds() const { return handle_cpu_seconds_; }
  const Status& status() const { return status_; }
  int last_map_bytes() const { return last_map_bytes_; }

  // Maps one scan; returns what to publish.
  Answer Handle(const SyncedScan& s) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu0 = ThreadCpuSeconds();
    Answer out;
    const mapper::ScanResult r = session_.AddScan(s.scan, *s.odometry);
    const PoseEstimate e = MakePoseEstimate(r, s.scan.utime, s.scan.scan_id, "clue", ThreadCpuSeconds() - cpu0);
    out.publications.push_back({p_.pose_channel, EncodeMessage(ToLcm(e))});
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
    if (r.outcome == mapper::ScanOutcome::kInserted) out.publications.push_back(MapMessage(s.scan.utime));
    // Live, an inserted scan is on disk before its POSE and map go out: a kill -9 loses none.
    const bool save_insert = live_ && p_.checkpoint_inserts && r.outcome == mapper::ScanOutcome::kInserted;
    if (!p_.checkpoint.empty() && (save_insert || (p_.checkpoint_every > 0 && ++since_checkpoint_ >= p_.checkpoint_every))) {
      SaveState();
      since_checkpoint_ = 0;
    }
    out.status = status_;
    handle_cpu_seconds_.push_back(ThreadCpuSeconds() - cpu0);
    handle_seconds_.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return out;
  }

  // Handle() on the worker thread: a failure inside the mapper must not kill the process or
  // lose later scans; the scan then gets no answer.
  Answer HandleOrLog(const SyncedScan& s) {
    try {
      return Handle(s);
    } catch (const std::exception& e) {
      MINENAV_LOG(kError) << "scan " << s.scan.scan_id << ": mapper failed: " << e.what();
      return {{}, status_};
    }
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

  // Bytes of the current map as CONTOUR_MAP, plain and compressed (for the summary line).
  std::pair<int, int> MapSizes() const {
    ContourMapMessage m;
    for (const auto& [id, c] : session_.map().contours()) m.contours.push_back({id, c.closed, c.points});
    return {ContourMapToLcm(m, 1 << 30).getEncodedSize(), ContourMapToLcm(m, 0).getEncodedSize()};
  }

 private:
  const ContourMapperNodeOptions& p_;
  mapper::MappingSession session_;
  bool live_;
  int since_checkpoint_ = 0;
  Status status_{heartbeat_t::OK, ""};
  int last_map_bytes_ = 0;
  std::vector<double> handle_seconds_, handle_cpu_seconds_;
};

// Scans the live worker's full queue pushed out: counted, logged at most once a second,
// and shown in HEARTBEAT (WARN while drops are recent). Node thread only.
class ContourMapperNode::QueueDrops {
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
  Status Combined(const Status& worker) const {
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

ContourMapperNode::ContourMapperNode(NodeRuntime& runtime, ContourMapperNodeOptions options,
                                     mapper::MappingSession session)
    : runtime_(runtime),
      options_(std::move(options)),
      batch_(runtime.batch()),
      core_(std::make_unique<Core>(options_, std::move(session), !batch_)),
      sync_({.max_odometry_gap_us = std::llround(options_.run.max_odometry_gap * 1e6)}),
      drops_(std::make_unique<QueueDrops>(options_.worker_queue_capacity)),
      worker_status_{heartbeat_t::OK, ""} {
  Subscribe();
  if (!batch_) {
    worker_ = std::make_unique<BackgroundWorker<SyncedScan, Answer>>(
        static_cast<size_t>(options_.worker_queue_capacity), [this](SyncedScan& s) { return core_->HandleOrLog(s); });
    runtime_.AddTimer(0.01, [this](int64_t) { PublishWorkerOutbox(); });
    if (options_.map_republish_period > 0) {
      // A resumed or loaded map goes out at once: nothing else would send it before an insert.
      if (core_->session().map().NumContours() > 0) Publish({{core_->MapMessage(runtime_.NowUtime())}, {}});
      runtime_.AddTimer(options_.map_republish_period / 4, [this](int64_t now) { RepublishMap(now); });
    }
  }
  runtime_.OnShutdown([this] { Finish(); });
}

// Without a shutdown (an exception before Run()): the thread stops, nothing is published.
ContourMapperNode::~ContourMapperNode() {
  if (worker_) worker_->Stop();
}

int ContourMapperNode::Run() {
  const int code = runtime_.Run();
  // A signal after the last event (in the final refinement) leaves the runtime's code 0;
  // damage in the log keeps its code (2).
  return kept_partial_ && code == 0 ? kExitInterrupted : code;
}

const mapper::MappingSession& ContourMapperNode::session() const { return core_->session(); }

int64_t ContourMapperNode::scans_dropped() const { return drops_->count(); }

void ContourMapperNode::Subscribe() {
  Bus& bus = runtime_.bus();
  minenav::Subscribe<odometry_t>(bus, options_.odometry_channel, [this](const odometry_t& m) {
    if (!sync_.AddOdometry(FromLcm(m)))
      MINENAV_LOG(kWarn) << options_.odometry_channel << " time went back: history cleared";
    Dispatch(false);
  });
  minenav::Subscribe<ladar_scan_t>(bus, options_.scan_channel, [this](const ladar_scan_t& m) {
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
      AnswerUnmapped(scan, "invalid scan: " + why);
      throw InputError("invalid scan " + std::to_string(m.scan_id) + ": " + why);
    }
    ++scans_received_;
    if (!sync_.AddScan(std::move(scan))) MINENAV_LOG(kWarn) << "scans waiting for odometry: dropped the oldest";
    Dispatch(false);
  });
}

void ContourMapperNode::Dispatch(bool at_shutdown) {
  for (SyncedScan& s : sync_.TakeReady(at_shutdown)) {
    if (!s.odometry) {
      ++no_odometry_;
      const std::string why = "no odometry within " + std::to_string(options_.run.max_odometry_gap) + " s";
      MINENAV_LOG(kWarn) << "scan " << s.scan.scan_id << " at " << s.scan.utime << ": " << why << "; skipped";
      AnswerUnmapped(s.scan, why);
      runtime_.SetStatus(heartbeat_t::WARN, "no odometry for a scan");
      continue;
    }
    if (!worker_) {
      MapNow(s);
      continue;
    }
    if (const std::optional<SyncedScan> dropped = worker_->Push(std::move(s))) {
      drops_->Count(dropped->scan);
      AnswerUnmapped(dropped->scan, drops_->PoseStatus());
    }
  }
}

void ContourMapperNode::MapNow(const SyncedScan& s) {
  const Answer answer = core_->Handle(s);
  Publish(answer);
  runtime_.SetStatus(answer.status.first, answer.status.second);
  if (batch_)
    std::fprintf(stderr, "\r[contour_mapper] scan %lld, %d contours, %.1f s   ",
                 static_cast<long long>(scans_received_), core_->session().map().NumContours(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

void ContourMapperNode::Publish(const Answer& answer) {
  Bus& bus = runtime_.bus();
  for (const Publication& pub : answer.publications) {
    bus.Publish(pub.channel, pub.bytes.data(), static_cast<int>(pub.bytes.size()));
    if (!batch_ && pub.channel == options_.map_channel) {
      last_map_ = pub.bytes;
      last_map_utime_ = runtime_.NowUtime();
    }
  }
}

void ContourMapperNode::RepublishMap(int64_t now_utime) {
  if (last_map_.empty() || now_utime - last_map_utime_ < std::llround(options_.map_republish_period * 1e6)) return;
  runtime_.bus().Publish(options_.map_channel, last_map_.data(), static_cast<int>(last_map_.size()));
  last_map_utime_ = now_utime;
}

void ContourMapperNode::PublishWorkerOutbox() {
  for (const Answer& answer : worker_->TakeOutbox()) {
    Publish(answer);
    worker_status_ = answer.status;
  }
  const auto [state, message] = drops_->Combined(worker_status_);
  runtime_.SetStatus(state, message);
}

void ContourMapperNode::AnswerUnmapped(const LadarScan& scan, const std::string& why) {
  minenav::Publish(runtime_.bus(), options_.pose_channel, UnmappedPose(scan, why));
}

void ContourMapperNode::StopWorker() {
  if (!worker_) return;
  // Only the scan under way is finished: draining a backlog took minutes (issue 11).
  std::deque<SyncedScan> not_mapped = worker_->Stop();
  for (SyncedScan& s : sync_.TakeReady(true)) not_mapped.push_back(std::move(s));  // waiting for odometry
  PublishWorkerOutbox();
  for (const SyncedScan& s : not_mapped) AnswerUnmapped(s.scan, "not mapped: the mapper stopped");
  not_mapped_at_stop_ = static_cast<int64_t>(not_mapped.size());
  LogLine(not_mapped.empty() ? LogLevel::kInfo : LogLevel::kWarn)
      << "stopping: " << not_mapped.size() << " queued scans not mapped";
  worker_.reset();
}

void ContourMapperNode::LogSummary() const {
  const auto& st = core_->session().state();
  const auto [plain, compressed] = core_->MapSizes();
  MINENAV_LOG(kInfo) << scans_received_ << " scans received: " << st.inserted << " inserted, " << st.tracked
                     << " tracked, " << st.refused << " refused, " << no_odometry_ << " without odometry"
                     << (batch_ ? ""
                                : ", " + std::to_string(drops_->count()) + " dropped (queue full), " +
                                      std::to_string(not_mapped_at_stop_) + " not mapped at the stop")
                     << "; median handling time " << Median(core_->handle_seconds()) << " s wall, "
                     << Median(core_->handle_cpu_seconds()) << " s CPU per scan; last CONTOUR_MAP "
                     << core_->last_map_bytes() << " bytes (map " << plain << " bytes plain, " << compressed
                     << " compressed)";
}

// The shutdown hook: the scans still waiting, the summary, the checkpoint, then either the
// final refinement and the outputs or, for a batch run cut short, the partial outputs.
void ContourMapperNode::Finish() {
  if (worker_) {
    StopWorker();
  } else {
    Dispatch(true);
  }
  if (batch_) std::fprintf(stderr, "\n");
  LogSummary();
  // Batch: cut short by a signal, before the end of the log or after it (the final
  // refinement would be the long part), or by damage in the log (the runtime then exits 2).
  const bool interrupted = batch_ && (runtime_.interrupted() || NodeRuntime::StopSignalled());
  if (batch_ && scans_received_ == 0 && !interrupted)
    throw InputError(runtime_.options().log + ": no " + options_.scan_channel + " messages");
  core_->SaveState();  // before the final refinement: a restart continues the same sequence
  if (interrupted) {
    if (!NodeRuntime::StopSignalled()) return KeepPartial("stopped at damage in the log");
    return KeepPartial(runtime_.interrupted() ? "interrupted before the end of the log" : "interrupted after the log");
  }
  if (core_->session().mapper().scans().empty()) {
    if (batch_) throw std::runtime_error("no scan could be inserted");
    MINENAV_LOG(kWarn) << "no scan inserted: no map written";
    return;
  }
  FinalRefinementAndOutputs();
}

void ContourMapperNode::FinalRefinementAndOutputs() {
  mapper::MappingSession& session = core_->session();
  const int rounds = options_.run.final_refinement_rounds;
  if (rounds > 0 && not_mapped_at_stop_ > 0) {
    MINENAV_LOG(kWarn) << "final refinement skipped: the mapper was behind when it stopped";
  } else if (rounds > 0) {
    mapper::ConcurrentRefinementOptions final_refinement = session.options().mapper.refinement;
    final_refinement.max_rounds = rounds;
    // Live, the stop signal has already come (it is how a live run ends): the refinement
    // runs to its end unless a second signal ends the process (the checkpoint is saved).
    if (!batch_) final_refinement.should_stop = {};
    const auto refined = session.RefineWith(final_refinement);
    MINENAV_LOG(kInfo) << "final refinement: " << refined.rounds << " rounds, " << refined.reason;
    if (refined.stopped) return KeepPartial("interrupted in the final refinement");
    Publish({{core_->MapMessage(runtime_.NowUtime(), 1)}, {}});
  }
  MINENAV_LOG(kInfo) << "wrote " << WriteOutputs(options_, session, Title(), "");
}

// What an interrupted batch run keeps, in one line.
void ContourMapperNode::KeepPartial(const std::string& what) {
  kept_partial_ = true;
  const mapper::MappingSession& session = core_->session();
  if (session.mapper().scans().empty()) {
    MINENAV_LOG(kWarn) << what << " before any scan was inserted: nothing written";
    return;
  }
  const auto& st = session.state();
  const std::string written = WriteOutputs(options_, session, Title(), ".partial");
  MINENAV_LOG(kWarn) << what << ": kept " << st.inserted << " inserted, " << st.tracked << " tracked and "
                     << st.refused << " refused of " << scans_received_
                     << " scans read, without the final refinement, in " << written;
}

}  // namespace minenav
