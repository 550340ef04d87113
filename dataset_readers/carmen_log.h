#pragma once
// Reading CARMEN log files (.clf, the text format of the Radish / Freiburg SLAM-benchmark
// logs: Intel, Freiburg 079, MIT CSAIL, Freiburg hospital) into the plain types our
// algorithms use. No LCM: `log_tool import-carmen` writes the result as an LCM log.
// The datasets and their quirks are described in shared/datasets/SOURCES.md; the
// metric they are scored with is in evaluation/relations.h (Kuemmerle et al. 2009).
//
// Lines read (everything else, e.g. RLASER, NEFF, SYNC, TRUEPOS, is counted and ignored):
//   FLASER n r1..rn  x y theta  odom_x odom_y odom_theta  ipc_timestamp host logger_timestamp
//   ROBOTLASER1 type start_angle fov angular_res max_range accuracy remission_mode
//               n r1..rn  m e1..em  laser_x laser_y laser_theta  robot_x robot_y robot_theta
//               tv rv forward_safety side_safety turn_axis  ipc_timestamp host logger_timestamp
//   ODOM x y theta tv rv accel  ipc_timestamp host logger_timestamp
//   PARAM name value ...   (robot_front_laser_max sets FLASER's maximum range)
//
// Conventions:
// - utime is the ipc_timestamp (the field before the host name) in microseconds, parsed
//   exactly from its decimal digits. The relations files of Kuemmerle 2009 name scans by
//   this time.
// - FLASER has no angles in the line: as CARMEN's own reader (carmen_laser_get_fov /
//   carmen_laser_get_angle_increment) the first beam is at -pi/2 and the step is 1 deg for
//   180/181 readings, 0.5 deg for 360/361, 0.25 deg for 400/401, else pi / (n - 1).
//   ROBOTLASER1 gives start angle and step in the line.
// - Maximum range: the line's (ROBOTLASER1), else PARAM robot_front_laser_max (FLASER),
//   else options.max_range; never above options.max_range, because the SICK LMS reports
//   "no return" as 81.83 m / 81.91 m codes that lie below some logs' declared maxima.
//   A reading at or beyond the maximum, or <= 0, is no return: stored as NaN.
// - sensor_offset is the laser pose relative to the robot pose of the same line
//   (robot^-1 * laser): fr079's laser sits 0.04 m behind the robot centre, the hospital's
//   0.22 m ahead, the others at the centre.
// - The robot pose of each laser line (FLASER's second triple, ROBOTLASER1's robot pose)
//   is that scan's odometry: CarmenLog::scan_odometry[i] belongs to scans[i]. mit-csail
//   has no ODOM lines and this is its only odometry.
//
// Time order. Everything is kept in FILE ORDER, which is the order things happened: in
// Intel the ipc timestamps go backwards 631 times between consecutive FLASER lines (and
// 602 times between ODOM lines), by up to 0.9 s, while the odometry in the same lines
// advances smoothly in file order; so the timestamps are jittered, not the lines
// shuffled. By default utime is the raw ipc time, because that is what the relations
// name. Consumers that need monotonic time have three safe choices:
//   - scan_id is the index of the scan in file order: strictly increasing, always;
//   - CarmenReadOptions::monotonic_times = true makes each stream's utime strictly
//     increasing (a time not after its predecessor becomes predecessor + 1 us); the
//     affected scans then no longer carry their relation time (score with raw times);
//   - MakeStrictlyIncreasing() does the same to any sequence of times afterwards.
// CarmenLogStats counts the reversals either way.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "common/scan.h"
#include "common/vehicle_state.h"

namespace minenav {

struct CarmenReadOptions {
  // m. Upper bound on every scan's maximum range; readings at or beyond the maximum are
  // no return. 80 m is the SICK LMS 2xx specified maximum (its no-return codes are 81.83
  // and 81.91 m).
  double max_range = 80.0;
  // m. Readings below this are no return (0 keeps all positive readings).
  double min_range = 0.0;
  // When true, scans, scan_odometry and odometry get strictly increasing utimes (see the
  // header comment). Default false: raw ipc times, as the relations files name them.
  bool monotonic_times = false;
  // bytes. A longer line is refused (InputError naming the line) as soon as this much of it
  // has been read: a CARMEN line is a few KB (Intel's FLASER lines ~1.5 KB, hospital's
  // ROBOTLASER1 ~3 KB), and a file whose lines are endless is not a log but, e.g., a
  // decompression bomb (3 MB of gzip expanding to one 3 GB line).
  size_t max_line_bytes = 1 << 20;
};

struct CarmenLogStats {
  int64_t lines = 0;               // every line of the file, blank and comment lines included
  int64_t flaser_lines = 0;
  int64_t robotlaser1_lines = 0;
  int64_t odom_lines = 0;
  int64_t param_lines = 0;
  int64_t ignored_lines = 0;       // other messages (RLASER, NEFF, SYNC, TRUEPOS, ...)
  int64_t no_return_readings = 0;  // readings stored as NaN (max range, <= 0, < min_range)
  int64_t scan_time_reversals = 0;      // scans whose raw utime is < the previous scan's
  int64_t odometry_time_reversals = 0;  // ODOM lines whose raw utime is < the previous one's
};

struct CarmenLog {
  // FLASER and ROBOTLASER1 lines in file order; scan_id = index, sensor_id = the message
  // name, scan_duration = 0 (not in the format).
  std::vector<LadarScan> scans;
  // One per scan, same index and utime: the robot (odometry) pose of the laser line,
  // seq = scan index; v, omega from ROBOTLASER1's tv, rv (0 for FLASER).
  std::vector<OdometryReading> scan_odometry;
  // ODOM lines in file order: pose, v = tv, omega = rv, seq = index.
  std::vector<OdometryReading> odometry;
  CarmenLogStats stats;
};

// Reads a CARMEN log: plain text, gzip or bzip2 (recognised by the file's first bytes, so
// .clf, .clf.gz, .clf.bz2 and .log.gz all work). The file is decompressed and parsed as a
// stream, one line in memory at a time. Throws InputError with one line naming the file
// (and the line number where there is one) and what is wrong for: an unreadable file;
// corrupt compressed data; a gzip or bzip2 stream that ends before its end marker (a file
// cut short: "truncated", not a shorter log); a line longer than max_line_bytes; a
// malformed FLASER / ROBOTLASER1 / ODOM / PARAM line. Messages quote at most 80 bytes of
// the offending text (then "...", non-printable bytes as \xHH).
CarmenLog ReadCarmenLog(const std::string& path, const CarmenReadOptions& options = {});

// The same for CARMEN text already in memory (same line limit); `source_name` names it in
// errors.
CarmenLog ParseCarmenLog(const std::string& text, const std::string& source_name,
                         const CarmenReadOptions& options = {});

// Makes times strictly increasing in place: a time not after its predecessor becomes the
// predecessor + 1 us. Returns how many were changed.
int64_t MakeStrictlyIncreasing(std::vector<int64_t>* utimes);

// Seconds to microseconds: with up to 6 decimals ("976052857.337530") exactly, digit by
// digit (a double holds only ~16 digits); any other finite number ("1.08499e-42", found in
// intel-corrected's ODOM lines) through a double, rounded. Returns false for anything else.
bool ParseCarmenTimestamp(const std::string& text, int64_t* utime);

}  // namespace minenav
