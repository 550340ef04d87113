#pragma once
// cutter as a node: the sump-shear cycle of tracker/cutter.h on the bus.
//
// The cut task arrives on CUT_TASK as a cutter_command_t: action SUMP starts a cut
// `sump_depth` m deep into the face line face_x1..y2 (map frame; a box cut into a whole face,
// or a slab cut into the part of a face beside a box cut; both points equal, e.g. all zero =
// find the face in CONTOUR_MAP straight ahead of the vehicle); action STOP with the seq of
// the cut under way cancels it (TASK_STATUS CANCELED "canceled by the sender"); the
// message's seq is the task id reported on TASK_STATUS. (CUTTER_COMMAND itself is what the
// cutter sends the vehicle's appendages, so the task has its own channel.)
//
// Repeat-safe (a coordinator re-sends each task until acknowledged): a SUMP or STOP whose
// seq is that of the cut under way or of the last one (ended, refused or canceled) changes
// nothing and is answered with that cut's latest TASK_STATUS, re-published.
//
// Subscribes CUT_TASK, POSE (pose_estimate_t; unconverged estimates are ignored), ODOMETRY
// (the prediction between estimates), CUTTER_STATE and CONTOUR_MAP; publishes DRIVE_COMMAND
// (every tick while a cut is active and one STOP when it ends, nothing otherwise),
// CUTTER_COMMAND, TASK_STATUS (on start, every second while active, and when it ends: DONE,
// or FAILED with the one-line reason) and HEARTBEAT (the step, or the reason it stopped).
// It acts on the fleet's own estimates only.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/config.h"
#include "common/node/node_runtime.h"
#include "minenav/task_status_t.hpp"
#include "tracker/cutter.h"
#include "tracker/cutter_messages.h"

namespace minenav {

struct CutterNodeOptions {
  std::string task_channel = "CUT_TASK";
  std::string pose_channel = "POSE";
  std::string odometry_channel = "ODOMETRY";
  std::string state_channel = "CUTTER_STATE";
  std::string map_channel = "CONTOUR_MAP";
  std::string drive_channel = "DRIVE_COMMAND";
  std::string command_channel = "CUTTER_COMMAND";
  std::string status_channel = "TASK_STATUS";
  double rate = 10.0;  // Hz
  CutterOptions cutter;
};

void DeclareOptions(ConfigSchema& schema, CutterNodeOptions& o);

class CutterNode {
 public:
  // Subscribes and adds the control timer (call after runtime.Start()).
  CutterNode(NodeRuntime& runtime, const CutterNodeOptions& options);
  int Run() { return runtime_.Run(); }
  const Cutter& cutter() const { return cutter_; }

 private:
  void Tick(int64_t now);
  void OnTask(const CutterCommand& task, int64_t now);
  void PublishStatus(int64_t now);
  // The latest TASK_STATUS again, stamped now (the acknowledgement of a repeated task).
  void Republish(int64_t now);

  NodeRuntime& runtime_;
  CutterNodeOptions options_;
  Cutter cutter_;
  std::optional<StampedPose> pose_;
  std::optional<CutterState> state_;
  std::vector<Segment> map_;
  int64_t last_status_at_ = 0;
  // DRIVE_COMMAND's seq: the cutter's own stream on a channel the tracker also drives (each
  // publisher numbers its messages, so a receiver or a log reader can count what it missed).
  int64_t drive_seq_ = 0;
  std::optional<task_status_t> last_status_;  // of the cut under way or the last one
  std::string last_step_;
};

}  // namespace minenav
