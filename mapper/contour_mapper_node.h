#pragma once
// The contour mapper as a node of the fleet (thesis chapter 4, CLUE): what the process
// contour_mapper is, apart from parsing its options. Unit-tested through FakeBus and LogBus
// (contour_mapper_node_test.cc); the process is a thin main over it.
//
// Each LADAR_SCAN is paired with ODOMETRY (common/node/scan_odometry_sync.h) and handed to
// a MappingSession (mapping_session.h, the policy batch and live share, so replaying a log
// live gives the batch map): every scan is answered by one pose_estimate_t on POSE (source
// "clue"; converged = false and the reason in status when it was refused, invalid, had no
// odometry, was dropped from a full queue or was still waiting at the stop), and every insert
// by contour_map_t on CONTOUR_MAP (version increasing, zlib-compressed above compress_above).
//
//   * Batch (runtime.batch(), --log): each scan is mapped as it is read; at the end of the
//     log the final refinement runs and --map-out, --poses-out and --svg-out are written.
//     Stopped by a signal (or damage in the log) they go to FILE.partial instead, without the
//     final refinement, with one line saying what was kept; Run() returns kExitInterrupted
//     (or the runtime's 2).
//   * Live: a BackgroundWorker (common/node/background_worker.h) owns the session while the
//     node runs: the node thread pairs and queues scans (at most worker_queue_capacity; a full
//     queue drops its oldest scan, which is counted, answered, logged at most once a second
//     and shown in HEARTBEAT), and publishes the worker's answers on a 10 ms timer. At the
//     stop the scan under way is finished, the queued ones are answered "not mapped", the
//     checkpoint is saved, and the final refinement runs unless scans were left unmapped.
//   * --checkpoint: saved every checkpoint_every handled scans and at the stop, before the
//     final refinement; --save-map beside it.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "common/config.h"
#include "common/node/background_worker.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/node_runtime.h"
#include "common/node/scan_odometry_sync.h"
#include "mapper/mapper_presets.h"
#include "mapper/mapping_session.h"

namespace minenav {

struct ContourMapperNodeOptions {
  // The session, the final refinement and the pairing with odometry (what a preset sets).
  mapper::MapperRunOptions run;
  std::string map_out;    // contour-map JSON written at the end (required in batch)
  std::string poses_out;  // poses CSV, one row per inserted or tracked scan
  std::string svg_out;    // picture of the map and the trajectory
  std::string checkpoint;  // resumed from when it exists, saved at the stop
  // Handled scans (inserted, tracked or refused) between checkpoints; 0 = only at the stop.
  // Every 10 is about 1 s of 10 Hz scans: a crash (kill -9, power) loses at most that, and a
  // checkpoint of a few MB writes in a few hundredths of a second (mapper/README.md).
  int checkpoint_every = 10;
  // s; live, CONTOUR_MAP is sent again when it has not changed for this long (0 = only on a
  // change), and at the start when resumed from a checkpoint or a map: a process that starts
  // late or restarts (the planner after kill -9) gets the map without waiting for the
  // vehicle to move. Receivers ignore a version they have (path and task planner, tracker).
  double map_republish_period = 2.0;
  // Live: also saved at every inserted scan (every metre or so of driving), before the scan's
  // POSE and map go out, so that a kill -9 loses no inserted scan (issue 16). Batch runs
  // ignore it: the log they replay is their record.
  bool checkpoint_inserts = true;
  std::string load_map;  // start from this contour map
  std::string save_map;  // contour map written at every checkpoint and at the stop
  std::string scan_channel = "LADAR_SCAN";
  std::string odometry_channel = "ODOMETRY";
  std::string pose_channel = "POSE";
  std::string map_channel = "CONTOUR_MAP";
  int compress_above = kContourMapCompressAbove;  // bytes
  // Scans; live, the most that wait for the mapper (100: 10 s of 10 Hz scans, about 2 MB of
  // 2048-point scans); a full queue drops its oldest scan.
  int worker_queue_capacity = 100;
};

// Declares every option of the node under `scope`: its own, the run's (mapper_presets.h:
// insert_min_translation, mapper.pose.final_threshold, ...), and as aliases the flat names the
// process has always accepted (max_rms_distance = mapper.max_rms_distance, ...).
void DeclareOptions(OptionScope scope, ContourMapperNodeOptions& o);

// Before anything is read (exit code 2 on failure): the options are consistent, and no output
// (--map-out, --poses-out, --svg-out, --save-map, --log-out, or their .partial) names an
// input (--log, --load-map, `config`, and --checkpoint, which is only read and written by
// design); --checkpoint names none of --log, --load-map, `config`.
void ValidateNodeOptions(const ContourMapperNodeOptions& o, const NodeOptions& node, const std::string& config);

// The session to start from, each with one log line: the checkpoint when it exists (it wins
// over --load-map), else --load-map, else an empty map. Its refinements stop within a step of
// SIGINT/SIGTERM (NodeRuntime::StopSignalled).
mapper::MappingSession OpenMappingSession(const ContourMapperNodeOptions& o);

class ContourMapperNode {
 public:
  // Subscribes on runtime.bus(): call after runtime.Start() or StartWith(). Live when
  // !runtime.batch(): the worker thread starts here.
  ContourMapperNode(NodeRuntime& runtime, ContourMapperNodeOptions options, mapper::MappingSession session);
  ~ContourMapperNode();
  ContourMapperNode(const ContourMapperNode&) = delete;
  ContourMapperNode& operator=(const ContourMapperNode&) = delete;

  // runtime.Run(): until the end of the log, a signal, RequestStop() or --run-for. Returns
  // the exit code: kExitInterrupted when a batch run kept partial outputs, else the runtime's.
  int Run();

  // After Run() (the worker has stopped): the session as it ended.
  const mapper::MappingSession& session() const;
  int64_t scans_received() const { return scans_received_; }
  int64_t scans_without_odometry() const { return no_odometry_; }
  int64_t scans_dropped() const;  // live: pushed out of the full queue
  int64_t scans_not_mapped_at_stop() const { return not_mapped_at_stop_; }
  bool kept_partial() const { return kept_partial_; }

 private:
  class Core;
  class QueueDrops;
  struct Answer;

  void Subscribe();
  void Dispatch(bool at_shutdown);
  void MapNow(const SyncedScan& s);
  void Publish(const Answer& answer);
  void PublishWorkerOutbox();
  void RepublishMap(int64_t now_utime);
  void AnswerUnmapped(const LadarScan& scan, const std::string& why);
  void StopWorker();
  void Finish();
  void FinalRefinementAndOutputs();
  void KeepPartial(const std::string& what);
  void LogSummary() const;
  std::string Title() const { return batch_ ? runtime_.options().log : "the live run"; }

  NodeRuntime& runtime_;
  const ContourMapperNodeOptions options_;
  const bool batch_;
  std::unique_ptr<Core> core_;  // the session and what is done with each of its results
  ScanOdometrySync sync_;
  std::unique_ptr<QueueDrops> drops_;
  std::unique_ptr<BackgroundWorker<SyncedScan, Answer>> worker_;  // live only: owns core_ while it runs
  std::pair<int8_t, std::string> worker_status_;  // of the last answer the worker made
  int64_t scans_received_ = 0, no_odometry_ = 0, not_mapped_at_stop_ = 0;
  bool kept_partial_ = false;  // batch: the outputs are FILE.partial
  std::vector<uint8_t> last_map_;  // live: the last CONTOUR_MAP sent (node thread), for late joiners
  int64_t last_map_utime_ = 0;     // when it was sent (the runtime's clock)
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace minenav
