// Pins the fingerprint of every message type. LCM refuses to decode a message whose
// fingerprint differs, so changing a type's fields silently makes every recorded log
// unreadable. If this test fails you changed a type: that is allowed only on purpose,
// with a new type name or a note in lcmtypes/README.md, and then the value is updated here.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "minenav/contour_map_t.hpp"
#include "minenav/contour_t.hpp"
#include "minenav/coordinator_command_t.hpp"
#include "minenav/cutter_command_t.hpp"
#include "minenav/cutter_state_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/line_segment_t.hpp"
#include "minenav/mission_node_t.hpp"
#include "minenav/mission_status_t.hpp"
#include "minenav/odometry_t.hpp"
#include "minenav/path_request_t.hpp"
#include "minenav/path_segment_t.hpp"
#include "minenav/path_t.hpp"
#include "minenav/pose2d_t.hpp"
#include "minenav/pose_estimate_t.hpp"
#include "minenav/task_plan_t.hpp"
#include "minenav/task_request_t.hpp"
#include "minenav/task_status_t.hpp"
#include "minenav/task_t.hpp"
#include "minenav/vehicle_truth_t.hpp"

namespace {

struct Pinned {
  std::string name;
  int64_t hash;
  int64_t actual;
};

TEST(LcmTypesTest, FingerprintsArePinned) {
  const std::vector<Pinned> pinned = {
      {"contour_map_t", 1415252279346109966LL, minenav::contour_map_t::getHash()},
      {"contour_t", 8024596247725125959LL, minenav::contour_t::getHash()},
      {"coordinator_command_t", -8440385620489131255LL, minenav::coordinator_command_t::getHash()},
      {"cutter_command_t", -8163100893728066272LL, minenav::cutter_command_t::getHash()},
      {"cutter_state_t", 6928058615450209422LL, minenav::cutter_state_t::getHash()},
      {"drive_command_t", -1454159458057979454LL, minenav::drive_command_t::getHash()},
      {"heartbeat_t", -4742075743124514646LL, minenav::heartbeat_t::getHash()},
      {"ladar_scan_t", -2038136047799717131LL, minenav::ladar_scan_t::getHash()},
      {"line_map_t", -419260473908764121LL, minenav::line_map_t::getHash()},
      {"line_segment_t", -6938642210381800720LL, minenav::line_segment_t::getHash()},
      {"mission_node_t", 5212168176119041012LL, minenav::mission_node_t::getHash()},  // issue 15
      {"mission_status_t", 7973969827392793868LL, minenav::mission_status_t::getHash()},  // issue 15: progress, waiting_for, the task tree
      {"odometry_t", 1879946957910835790LL, minenav::odometry_t::getHash()},
      {"path_request_t", -9076065102670345754LL, minenav::path_request_t::getHash()},  // issue 13: allow_unknown
      {"path_segment_t", 3440628198772269525LL, minenav::path_segment_t::getHash()},
      {"path_t", -1701602323202045816LL, minenav::path_t::getHash()},
      {"pose2d_t", -1647330039494046938LL, minenav::pose2d_t::getHash()},
      {"pose_estimate_t", 1641264035168771739LL, minenav::pose_estimate_t::getHash()},
      {"task_plan_t", -7475414412055944702LL, minenav::task_plan_t::getHash()},  // issue 15: request_id, status, reason
      {"task_status_t", 1986406185136541687LL, minenav::task_status_t::getHash()},
      {"task_request_t", -4740743851739562217LL, minenav::task_request_t::getHash()},  // issue 15
      {"task_t", 4790446032985350541LL, minenav::task_t::getHash()},  // issue 15: face, clearance, allow_reverse, appendages
      {"vehicle_truth_t", 3644935162126682736LL, minenav::vehicle_truth_t::getHash()},
  };
  for (const auto& p : pinned) EXPECT_EQ(p.actual, p.hash) << p.name << " changed: old logs will not decode";
}

TEST(LcmTypesTest, ZeroInitialisedMessagesRoundTrip) {
  minenav::ladar_scan_t scan{};
  scan.utime = 123;
  scan.num_ranges = 3;
  scan.ranges = {1.0f, 2.0f, 3.0f};
  std::vector<uint8_t> buf(static_cast<size_t>(scan.getEncodedSize()));
  ASSERT_EQ(scan.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  minenav::ladar_scan_t back{};
  ASSERT_EQ(back.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  EXPECT_EQ(back.utime, 123);
  EXPECT_EQ(back.ranges, scan.ranges);
  // A truncated payload does not decode, and a different type is refused by fingerprint.
  EXPECT_LT(back.decode(buf.data(), 0, static_cast<int>(buf.size()) - 1), 0);
  minenav::odometry_t odo{};
  EXPECT_LT(odo.decode(buf.data(), 0, static_cast<int>(buf.size())), 0);
}

}  // namespace
