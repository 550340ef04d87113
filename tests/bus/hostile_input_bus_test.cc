// Issue 11, hostile input on the bus: the live contour_mapper and iconic_pose_estimator
// inside a private network namespace (tests/bus/private_net.sh sets
// MINENAV_IN_PRIVATE_NET and LCM_DEFAULT_URL with a port of its own), each under a
// memory bound (tests/limited_process.h), fed by the test: a vehicle standing in a small
// room, ODOMETRY at 20 Hz (wall-clock stamps) and a scan at 10 Hz stamped 10 ms before the
// odometry reading that follows it, so every scan waits for that reading and is
// interpolated (common/node/scan_odometry_sync.h).
//
//   * Counts that lie (tests/hostile_messages.h): one packet of 34 to 92 bytes whose
//     array count is 2^24..2^31-1. The process must stay up, its peak RSS must stay under
//     300 MB, HEARTBEAT.messages_bad must go up, and the scans that follow must get a
//     converged pose. Unfixed, LCM 1.3.1 either overflows `sizeof(T) * count` and reads
//     past the buffer (SIGSEGV after zero-filling 2 GiB) or zero-fills 1-2 GiB before it
//     notices the payload is short.
//   * Timestamps that lie: a scan stamped INT64_MAX must not hold up the scans behind it
//     (unfixed: no pose for ~10 s, until 100 scans queue up); ODOMETRY stamped INT64_MAX
//     interleaved with the real odometry must not starve the real scans (unfixed: each one
//     clears the history and most scans are skipped for "no odometry") and HEARTBEAT must
//     say something is wrong; a scan stamped INT64_MIN must be refused (unfixed:
//     PoseAtTime's `after->utime - utime` overflows and the scan is mapped).

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "common/node/bus.h"
#include "common/node/conversions.h"
#include "common/node/lcm_bus.h"
#include "mapper/test_world.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "tests/bus/private_bus_test.h"
#include "tests/hostile_messages.h"
#include "tests/temp_dir.h"
#include "tests/limited_process.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::kMaxPeakRssKb;
using testing::kSlowdown;

// ODOMETRY ticks (50 ms) per scan: 10 Hz scans, slower under ASan so that a late pose means
// a blocked pipeline, not a process that cannot keep up.
constexpr int kTicksPerScan = testing::kUnderAddressSanitizer ? 6 : 2;
using testing::LimitedProcess;

enum class Target { kContourMapper, kIpe };

std::string ProcessName(Target t) { return t == Target::kContourMapper ? "contour_mapper" : "iconic_pose_estimator"; }
std::string PoseChannel(Target t) { return t == Target::kContourMapper ? "POSE" : "POSE_IPE"; }

int64_t RealtimeUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }


struct SeenPose {
  pose_estimate_t msg;
  Clock::time_point at;
};
struct SeenHeartbeat {
  heartbeat_t msg;
  Clock::time_point at;
};

// How the scans of a list fared.
struct PoseTally {
  int sent = 0, converged = 0, refused = 0, missing = 0, late = 0;
  double worst_latency_s = 0.0;
  std::map<std::string, int> refusals;  // status -> count

  std::string Describe() const {
    std::ostringstream os;
    os << sent << " scans sent: " << converged << " converged, " << refused << " refused, " << missing
       << " without any pose, " << late << " late; worst latency " << worst_latency_s << " s";
    for (const auto& [status, n] : refusals) os << "\n  " << n << "x refused: " << status;
    return os.str();
  }
};

class HostileBusTest : public testing::PrivateBusTest {
 protected:
  void SetUp() override {
    testing::PrivateBusTest::SetUp();
    if (HasFatalFailure()) return;
    mapper::testing::ScanSpec spec;
    spec.range_sigma = 0.01;
    scan_ = mapper::testing::MakeScan(mapper::testing::SmallRoomWorld(), pose_, spec);
    scan_.sensor_id = "typhoon";
  }

  // Starts the process under test (memory-bounded), waits for its first HEARTBEAT and,
  // for the IPE, gives it the room as LINE_MAP (without --map it also subscribes
  // CONTOUR_MAP, which the map tests need).
  void Start(Target target) {
    target_ = target;
    bus_ = std::make_unique<LcmBus>(url_, 10000);
    Subscribe<pose_estimate_t>(*bus_, PoseChannel(target), [this](const pose_estimate_t& m) {
      poses_.emplace(m.scan_id, SeenPose{m, Clock::now()});
    });
    Subscribe<heartbeat_t>(*bus_, "HEARTBEAT", [this](const heartbeat_t& m) {
      if (process_ && m.pid == process_->pid() && m.process == ProcessName(target_))
        heartbeats_.push_back({m, Clock::now()});
    });
    const std::string run_for = std::to_string(static_cast<int>(120 * kSlowdown));
    std::vector<std::string> argv;
    if (target == Target::kContourMapper) {
      argv = {MINENAV_CONTOUR_MAPPER_BIN, "--heartbeat-period", "0.2", "--run-for", run_for,
              "--insert-min-translation", "1", "--insert-min-rotation", "0.5", "--final-refinement-rounds", "0"};
    } else {
      argv = {MINENAV_IPE_BIN, "--heartbeat-period", "0.2", "--run-for", run_for, "--mode", "surveyed",
              "--min-threshold", "0.15"};
    }
    process_ = std::make_unique<LimitedProcess>(argv, dir_ / "process.txt");
    ASSERT_TRUE(Pump(20.0 * kSlowdown, [&] { return !heartbeats_.empty() || !process_->Running(); }) &&
                process_->Running())
        << "no HEARTBEAT from " << ProcessName(target) << " within 20 s (" << testing::DescribeExit(process_->Wait(0))
        << "):\n"
        << process_->OutputTail();
    if (target == Target::kIpe) {
      const line_map_t room = SegmentsToLcm(mapper::testing::SmallRoomWorld(), RealtimeUs(), 1, "room");
      bool taken = false;
      for (int attempt = 0; attempt < 30 && !taken; ++attempt) {
        Publish(*bus_, "LINE_MAP", room);  // the same version again is ignored
        taken = Pump(0.5 * kSlowdown, [&] { return LatestHeartbeat().messages_in > 0; });
      }
      ASSERT_TRUE(taken) << "iconic_pose_estimator did not take the LINE_MAP:\n" << process_->OutputTail();
    }
  }

  // Handles messages for up to `seconds`, until `done` returns true; returns done().
  bool Pump(double seconds, const std::function<bool()>& done) {
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) {
      if (done()) return true;
      bus_->HandleFor(10'000);
    }
    return done();
  }
  void PumpFor(double seconds) { Pump(seconds, [] { return false; }); }

  // The vehicle's sensors for `seconds`: every 50 ms an ODOMETRY reading stamped now; every
  // 100 ms (every 300 ms under ASan, where the mapper cannot keep up with 10 Hz), published
  // just before that reading, a scan stamped 10 ms before it (newer than the previous
  // reading, so the scan waits for this one and its pose is interpolated).
  // With `hostile_odometry`, an ODOMETRY stamped INT64_MAX follows every real reading
  // (20 Hz, interleaved). Returns the ids of the scans sent.
  std::vector<int64_t> Drive(double seconds, bool hostile_odometry = false) {
    std::vector<int64_t> sent;
    auto next = Clock::now();
    const auto end = next + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) {
      const int64_t now = RealtimeUs();
      if (tick_++ % kTicksPerScan == 0) sent.push_back(SendScan(now - 10'000));
      OdometryReading o;
      o.utime = now;
      o.seq = ++odometry_seq_;
      o.pose = pose_;
      Publish(*bus_, "ODOMETRY", ToLcm(o));
      if (hostile_odometry) {
        o.utime = std::numeric_limits<int64_t>::max();
        o.seq = ++odometry_seq_;
        Publish(*bus_, "ODOMETRY", ToLcm(o));
      }
      next += std::chrono::milliseconds(50);
      while (Clock::now() < next) {
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(next - Clock::now()).count();
        bus_->HandleFor(std::max<int64_t>(1000, left));
      }
    }
    return sent;
  }

  // Publishes the room scan stamped `utime`; returns its scan id.
  int64_t SendScan(int64_t utime, int64_t scan_id = -1) {
    LadarScan s = scan_;
    s.utime = utime;
    s.scan_id = scan_id >= 0 ? scan_id : ++last_scan_id_;
    sent_at_[s.scan_id] = Clock::now();
    Publish(*bus_, "LADAR_SCAN", ToLcm(s));
    return s.scan_id;
  }

  // Waits for the poses of `ids` (up to 3 s after the last was sent) and counts them; a
  // pose later than `prompt_s` after its scan was sent is late.
  PoseTally Tally(const std::vector<int64_t>& ids, double prompt_s = 1e9) {
    Pump(3.0 * kSlowdown, [&] {
      for (int64_t id : ids)
        if (!poses_.count(id)) return false;
      return true;
    });
    PoseTally t;
    for (int64_t id : ids) {
      ++t.sent;
      const auto it = poses_.find(id);
      if (it == poses_.end()) {
        ++t.missing;
        continue;
      }
      const double latency = Seconds(it->second.at - sent_at_[id]);
      t.worst_latency_s = std::max(t.worst_latency_s, latency);
      if (latency > prompt_s) ++t.late;
      if (it->second.msg.converged) {
        ++t.converged;
      } else {
        ++t.refused;
        ++t.refusals[it->second.msg.status];
      }
    }
    return t;
  }

  heartbeat_t LatestHeartbeat() const { return heartbeats_.empty() ? heartbeat_t{} : heartbeats_.back().msg; }

  // Valid scans for a second; at least half must be mapped, or the test proves nothing.
  void WarmUp() {
    const PoseTally t = Tally(Drive(1.0));
    ASSERT_GE(t.converged, t.sent / 2) << "warm-up: " << ProcessName(target_)
                                       << " must map valid scans before the hostile input: " << t.Describe() << "\n"
                                       << process_->OutputTail();
  }

  // Handles messages for a second after hostile input, then as long as the process is
  // busy (unfixed, zero-filling gigabytes and then reading past the buffer take a few
  // seconds of CPU before the crash), at most 10 s more.
  void Settle() {
    PumpFor(1.0 * kSlowdown);
    const auto end = Clock::now() + std::chrono::duration<double>(10.0 * kSlowdown);
    while (Clock::now() < end && process_->Running()) {
      const double cpu0 = process_->CpuSeconds();
      PumpFor(0.3);
      const double cpu1 = process_->CpuSeconds();
      if (cpu0 < 0 || cpu1 < 0 || cpu1 - cpu0 < 0.1) break;  // idle (or gone)
    }
  }

  // The process is still running and its peak RSS stayed under the bound.
  void ExpectAliveAndBounded(const std::string& after) {
    const bool running = process_->Running();
    const int64_t peak = process_->PeakRssKb();
    ASSERT_TRUE(running) << ProcessName(target_) << " died after " << after << ": "
                                     << testing::DescribeExit(process_->Wait(0)) << ", peak RSS " << peak / 1024
                                     << " MB; its output:\n"
                                     << process_->OutputTail();
    EXPECT_LT(peak, kMaxPeakRssKb) << ProcessName(target_) << " reached a peak RSS of " << peak / 1024 << " MB after "
                                   << after << " (bound " << kMaxPeakRssKb / 1024
                                   << " MB): the payload made it allocate what the packet cannot hold";
  }

  // SIGTERM; the process must stop cleanly.
  void Stop() {
    if (!process_ || !process_->Running()) return;
    process_->Signal(SIGTERM);
    const auto code = process_->Wait(20.0 * kSlowdown);
    EXPECT_TRUE(code.has_value() && *code == 0)
        << ProcessName(target_) << " did not stop cleanly on SIGTERM: " << testing::DescribeExit(code) << "\n"
        << process_->OutputTail();
  }

  void TearDown() override { Stop(); }

  testing::TempDir dir_{"minenav_hostile_bus"};
  Target target_ = Target::kContourMapper;
  std::unique_ptr<LcmBus> bus_;
  std::unique_ptr<LimitedProcess> process_;
  const Pose2 pose_{3.0, 9.0, 0.3};  // where the vehicle stands in SmallRoomWorld
  LadarScan scan_;
  int64_t tick_ = 0, odometry_seq_ = 0, last_scan_id_ = 0;
  std::map<int64_t, Clock::time_point> sent_at_;
  std::multimap<int64_t, SeenPose> poses_;  // by scan_id
  std::vector<SeenHeartbeat> heartbeats_;
};

// ---------------------------------------------------------------------------------------
// Counts that lie.

struct HostileCase {
  std::string name;  // test name suffix
  Target target;
  std::string channel;
  std::function<std::vector<uint8_t>()> payload;
  std::string what;
};

void PrintTo(const HostileCase& c, std::ostream* os) { *os << c.name; }

class HostileCountTest : public HostileBusTest, public ::testing::WithParamInterface<HostileCase> {};

TEST_P(HostileCountTest, ProcessSurvivesWithBoundedMemoryCountsTheMessageAndGoesOn) {
  const HostileCase& c = GetParam();
  ASSERT_NO_FATAL_FAILURE(Start(c.target));
  ASSERT_NO_FATAL_FAILURE(WarmUp());
  const std::vector<uint8_t> payload = c.payload();
  const std::string what = c.what + " (" + std::to_string(payload.size()) + " bytes) on " + c.channel;
  const int64_t bad_before = LatestHeartbeat().messages_bad;

  ASSERT_TRUE(bus_->Publish(c.channel, payload.data(), static_cast<int>(payload.size())));
  Settle();  // unfixed, this is when it zero-fills gigabytes and crashes
  ASSERT_NO_FATAL_FAILURE(ExpectAliveAndBounded(what));

  EXPECT_TRUE(Pump(3.0 * kSlowdown, [&] { return LatestHeartbeat().messages_bad > bad_before; }))
      << "HEARTBEAT.messages_bad stayed at " << LatestHeartbeat().messages_bad << " after " << what
      << ": a payload that cannot be decoded must be counted as bad\n"
      << process_->OutputTail();
  const PoseTally t = Tally(Drive(1.5));
  EXPECT_GE(t.converged, t.sent - 1) << "after " << what << ", the valid scans must still be mapped: " << t.Describe()
                                     << "\n"
                                     << process_->OutputTail();
  ASSERT_NO_FATAL_FAILURE(ExpectAliveAndBounded(what + " and the valid scans after it"));
}

std::string CaseName(const ::testing::TestParamInfo<HostileCase>& info) { return info.param.name; }

HostileCase ScanCase(Target target, const std::string& name, int32_t num_ranges, int32_t num_intensities,
                     const std::string& what) {
  return {name, target, "LADAR_SCAN",
          [=] { return testing::ScanWithCounts(num_ranges, num_intensities, RealtimeUs(), 1'000'000); }, what};
}

// Item 1 (overflowing counts: 2^29 floats, sizeof * count wraps to INT_MIN) and item 4
// (2^28 floats: 1 GiB zero-filled before the short payload is noticed).
std::vector<HostileCase> ScanCases(Target target) {
  return {
      ScanCase(target, "ScanNumRanges2p29", testing::kCount2p29, 0, "ladar_scan_t with num_ranges = 2^29"),
      ScanCase(target, "ScanNumIntensities2p29", 0, testing::kCount2p29, "ladar_scan_t with num_intensities = 2^29"),
      ScanCase(target, "ScanNumRanges2p28", testing::kCount2p28, 0, "ladar_scan_t with num_ranges = 2^28"),
  };
}

INSTANTIATE_TEST_SUITE_P(ContourMapperScans, HostileCountTest, ::testing::ValuesIn(ScanCases(Target::kContourMapper)),
                         CaseName);
INSTANTIATE_TEST_SUITE_P(IpeScans, HostileCountTest, ::testing::ValuesIn(ScanCases(Target::kIpe)), CaseName);

// Items 2 and 4 on the IPE's map channels (it subscribes them when it has no --map).
INSTANTIATE_TEST_SUITE_P(
    IpeMaps, HostileCountTest,
    ::testing::Values(
        HostileCase{"ContourNumPoints2p29", Target::kIpe, "CONTOUR_MAP",
                    [] { return testing::ContourMapWithPointCount(testing::kCount2p29); },
                    "contour_map_t holding a contour_t with num_points = 2^29"},
        HostileCase{"CompressedContourNumPoints2p29", Target::kIpe, "CONTOUR_MAP",
                    [] { return testing::CompressedContourMap(testing::ContourMapWithPointCount(testing::kCount2p29)); },
                    "zlib-compressed contour_map_t whose payload inflates to a contour with num_points = 2^29"},
        HostileCase{"ContourMapNumContours2p24", Target::kIpe, "CONTOUR_MAP",
                    [] { return testing::ContourMapWithContourCount(testing::kCount2p24); },
                    "contour_map_t with num_contours = 2^24"},
        HostileCase{"ContourMapPayloadSizeMax", Target::kIpe, "CONTOUR_MAP",
                    [] { return testing::ContourMapWithPayloadSize(testing::kCountMax); },
                    "contour_map_t with payload_size = 2^31-1"},
        HostileCase{"LineMapNumSegments2p26", Target::kIpe, "LINE_MAP",
                    [] { return testing::LineMapWithSegmentCount(testing::kCount2p26); },
                    "line_map_t with num_segments = 2^26"}),
    CaseName);

// ---------------------------------------------------------------------------------------
// Timestamps that lie (item 5).

class HostileTimestampTest : public HostileBusTest, public ::testing::WithParamInterface<Target> {};

void PrintTo(Target t, std::ostream* os) { *os << ProcessName(t); }

std::string TargetName(const ::testing::TestParamInfo<Target>& info) {
  return info.param == Target::kContourMapper ? "ContourMapper" : "Ipe";
}

constexpr int64_t kHostileScanId = 900'000;

// The scan with id `id` was refused visibly: no converged pose for it, and either a pose
// saying it was not converged or HEARTBEAT.messages_bad above `bad_before`.
void ExpectRefused(const std::multimap<int64_t, SeenPose>& poses, int64_t id,
                   int64_t bad_before, const heartbeat_t& latest, const std::string& what, const std::string& output) {
  bool converged = false, refused = false;
  std::string status;
  for (auto [it, end] = poses.equal_range(id); it != end; ++it) {
    converged = converged || it->second.msg.converged;
    refused = refused || !it->second.msg.converged;
    status = it->second.msg.status;
  }
  EXPECT_FALSE(converged) << what << " was mapped (converged pose, status '" << status
                          << "'): a scan stamped outside any sane time must be refused\n"
                          << output;
  EXPECT_TRUE(refused || latest.messages_bad > bad_before)
      << what << " was neither refused on the pose channel nor counted in HEARTBEAT.messages_bad (" << bad_before
      << " before, " << latest.messages_bad << " now)\n"
      << output;
}

TEST_P(HostileTimestampTest, ScanStampedInt64MaxDoesNotHoldUpTheScansAfterIt) {
  ASSERT_NO_FATAL_FAILURE(Start(GetParam()));
  ASSERT_NO_FATAL_FAILURE(WarmUp());
  const int64_t bad_before = LatestHeartbeat().messages_bad;
  SendScan(std::numeric_limits<int64_t>::max(), kHostileScanId);
  const std::vector<int64_t> after = Drive(3.0);
  const double prompt_s = 1.0 * kSlowdown;
  const PoseTally t = Tally(after, prompt_s);
  EXPECT_GE(t.converged, t.sent - 1) << "after a scan stamped INT64_MAX: " << t.Describe() << "\n"
                                     << process_->OutputTail();
  EXPECT_LE(t.late + t.missing, 1) << "the scans after one stamped INT64_MAX must get their pose within " << prompt_s
                                   << " s each (unfixed they wait ~10 s behind it): " << t.Describe();
  ExpectRefused(poses_, kHostileScanId, bad_before, LatestHeartbeat(), "the scan stamped INT64_MAX",
                process_->OutputTail());
  ASSERT_NO_FATAL_FAILURE(ExpectAliveAndBounded("a scan stamped INT64_MAX"));
}

TEST_P(HostileTimestampTest, OdometryStampedInt64MaxDoesNotStarveTheRealScans) {
  ASSERT_NO_FATAL_FAILURE(Start(GetParam()));
  ASSERT_NO_FATAL_FAILURE(WarmUp());
  const size_t heartbeats_before = heartbeats_.size();
  const auto hostile_start = Clock::now();
  const std::vector<int64_t> during = Drive(3.0, /*hostile_odometry=*/true);
  const PoseTally t = Tally(during);
  EXPECT_GE(t.converged, 0.9 * t.sent)
      << "with ODOMETRY stamped INT64_MAX interleaved at 20 Hz, the real scans must still be mapped (unfixed each "
         "one clears the odometry history and the scans are skipped): "
      << t.Describe() << "\n"
      << process_->OutputTail();

  // HEARTBEAT must not be a plain OK while it rejects odometry: WARN (or worse), or a
  // message, within the first 1.5 s (7 heartbeats) of the hostile stream.
  std::vector<std::string> seen;
  bool flagged = false;
  for (size_t i = heartbeats_before; i < heartbeats_.size(); ++i) {
    const SeenHeartbeat& h = heartbeats_[i];
    const double at = Seconds(h.at - hostile_start);
    if (at < 0.1 || at > 1.5 * kSlowdown) continue;
    seen.push_back("state " + std::to_string(h.msg.state) + " '" + h.msg.message + "' bad " +
                   std::to_string(h.msg.messages_bad));
    if (h.msg.state != heartbeat_t::OK || !h.msg.message.empty()) flagged = true;
  }
  std::string list;
  for (const std::string& s : seen) list += "\n  " + s;
  EXPECT_FALSE(seen.empty()) << "no HEARTBEAT during the hostile odometry";
  EXPECT_TRUE(flagged) << "HEARTBEAT stayed a plain OK with no message while ODOMETRY stamped INT64_MAX arrived "
                          "at 20 Hz; heartbeats in the first 1.5 s:"
                       << list;

  // And once the hostile stream stops, everything is mapped again.
  const PoseTally after = Tally(Drive(1.0));
  EXPECT_GE(after.converged, after.sent - 1) << "after the hostile odometry stopped: " << after.Describe();
  ASSERT_NO_FATAL_FAILURE(ExpectAliveAndBounded("ODOMETRY stamped INT64_MAX"));
}

TEST_P(HostileTimestampTest, ScanStampedInt64MinIsRefused) {
  ASSERT_NO_FATAL_FAILURE(Start(GetParam()));
  ASSERT_NO_FATAL_FAILURE(WarmUp());
  const int64_t bad_before = LatestHeartbeat().messages_bad;
  SendScan(std::numeric_limits<int64_t>::min(), kHostileScanId + 1);
  const PoseTally t = Tally(Drive(1.5));
  PumpFor(0.5);  // a heartbeat after the last scan
  ExpectRefused(poses_, kHostileScanId + 1, bad_before, LatestHeartbeat(), "the scan stamped INT64_MIN",
                process_->OutputTail());
  EXPECT_GE(t.converged, t.sent - 1) << "after a scan stamped INT64_MIN: " << t.Describe();
  ASSERT_NO_FATAL_FAILURE(ExpectAliveAndBounded("a scan stamped INT64_MIN"));
}

INSTANTIATE_TEST_SUITE_P(ContourMapper, HostileTimestampTest, ::testing::Values(Target::kContourMapper), TargetName);
INSTANTIATE_TEST_SUITE_P(Ipe, HostileTimestampTest, ::testing::Values(Target::kIpe), TargetName);

}  // namespace
}  // namespace minenav
