#include "common/node/bus.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/fake_bus.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/odometry_t.hpp"

namespace minenav {
namespace {

odometry_t MakeOdometry(int64_t utime) {
  odometry_t m{};
  m.utime = utime;
  m.seq = utime / 10;
  m.pose.x = 1.5;
  m.pose.y = -2.0;
  m.pose.theta = 0.25;
  m.v = 0.076;
  return m;
}

TEST(ResolveLcmUrl, FlagThenEnvironmentThenDefault) {
  ::unsetenv("LCM_DEFAULT_URL");
  EXPECT_EQ(ResolveLcmUrl(""), kDefaultLcmUrl);
  ::setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7701?ttl=0", 1);
  EXPECT_EQ(ResolveLcmUrl(""), "udpm://239.255.76.67:7701?ttl=0");
  EXPECT_EQ(ResolveLcmUrl("memq://"), "memq://");
  ::unsetenv("LCM_DEFAULT_URL");
}

TEST(ChannelMatcher, LiteralAndPattern) {
  EXPECT_TRUE(ChannelMatcher("POSE").Matches("POSE"));
  EXPECT_FALSE(ChannelMatcher("POSE").Matches("POSE_FPE"));
  EXPECT_TRUE(ChannelMatcher("POSE.*").Matches("POSE_FPE"));
  EXPECT_FALSE(ChannelMatcher("POSE.*").Matches("XPOSE"));  // anchored like LCM
  EXPECT_TRUE(ChannelMatcher(".*").Matches("ANYTHING"));
  EXPECT_THROW(ChannelMatcher("POSE("), std::invalid_argument);
}

TEST(TypedHelpers, RoundTripThroughTheBus) {
  FakeBus bus;
  std::vector<odometry_t> got;
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t& m) { got.push_back(m); });
  ASSERT_TRUE(Publish(bus, "ODOMETRY", MakeOdometry(100)));
  ASSERT_EQ(bus.published().size(), 1u);
  bus.Inject("ODOMETRY", bus.published()[0].data, 123);
  EXPECT_EQ(bus.HandleFor(0), 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].utime, 100);
  EXPECT_DOUBLE_EQ(got[0].pose.x, 1.5);
  EXPECT_DOUBLE_EQ(got[0].v, 0.076);
  EXPECT_EQ(bus.counters().messages_in, 1);
  EXPECT_EQ(bus.counters().messages_bad, 0);
  EXPECT_EQ(bus.counters().published, 1);
}

TEST(TypedHelpers, HandlerCanSeeChannelAndReceiveTime) {
  FakeBus bus;
  std::string channel;
  int64_t utime = 0;
  Subscribe<odometry_t>(bus, "ODOM.*", [&](const RawMessage& raw, const odometry_t&) {
    channel = std::string(raw.channel);
    utime = raw.utime;
  });
  bus.InjectMessage("ODOMETRY_2", MakeOdometry(5), 777);
  bus.HandleFor(0);
  EXPECT_EQ(channel, "ODOMETRY_2");
  EXPECT_EQ(utime, 777);
}

TEST(TypedHelpers, WrongFingerprintIsCountedNotThrown) {
  FakeBus bus;
  int handled = 0;
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t&) { ++handled; });
  drive_command_t other{};  // a valid message of another type on this channel
  bus.InjectMessage("ODOMETRY", other);
  EXPECT_NO_THROW(bus.HandleFor(0));
  EXPECT_EQ(handled, 0);
  EXPECT_EQ(bus.counters().messages_bad, 1);
  EXPECT_EQ(bus.bad_by_channel().at("ODOMETRY"), 1);
}

TEST(TypedHelpers, TruncatedAndGarbagePayloadsAreCounted) {
  FakeBus bus;
  int handled = 0;
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t&) { ++handled; });
  std::vector<uint8_t> bytes = EncodeMessage(MakeOdometry(1));
  for (size_t cut : {size_t{0}, size_t{4}, size_t{8}, bytes.size() / 2, bytes.size() - 1}) {
    bus.Inject("ODOMETRY", std::vector<uint8_t>(bytes.begin(), bytes.begin() + static_cast<long>(cut)));
  }
  bus.Inject("ODOMETRY", std::vector<uint8_t>(300, 0xAB));
  bus.Inject("ODOMETRY", bytes);  // and a good one still goes through afterwards
  EXPECT_EQ(bus.HandleFor(0), 7);
  EXPECT_EQ(handled, 1);
  EXPECT_EQ(bus.counters().messages_bad, 6);
  EXPECT_EQ(bus.counters().messages_in, 1);
}

TEST(TypedHelpers, CorruptArrayCountDoesNotEscape) {
  // Right fingerprint, but num_ranges = -5: the generated decoder throws length_error
  // from vector::resize; it must come back as a bad message.
  ladar_scan_t scan{};
  scan.sensor_id = "typhoon";
  scan.num_ranges = 2;
  scan.ranges = {1.0f, 2.0f};
  std::vector<uint8_t> bytes = EncodeMessage(scan);
  // num_ranges sits after utime, scan_id, sensor_id (4 + 8), sensor_offset (24), 6 floats.
  const size_t offset = 8 + 8 + 8 + 4 + 8 + 24 + 6 * 4;
  const uint8_t minus_five[4] = {0xFF, 0xFF, 0xFF, 0xFB};
  std::memcpy(bytes.data() + offset, minus_five, 4);
  FakeBus bus;
  int handled = 0;
  Subscribe<ladar_scan_t>(bus, "LADAR_SCAN", [&](const ladar_scan_t&) { ++handled; });
  bus.Inject("LADAR_SCAN", bytes);
  EXPECT_NO_THROW(bus.HandleFor(0));
  EXPECT_EQ(handled, 0);
  EXPECT_EQ(bus.counters().messages_bad, 1);
}

TEST(TypedHelpers, HandlerExceptionsAreBadMessages) {
  FakeBus bus;
  Subscribe<drive_command_t>(bus, "DRIVE_COMMAND", [](const drive_command_t& m) {
    FromLcm(m);  // throws InputError for an unknown mode
  });
  drive_command_t bad{};
  bad.mode = 42;
  bus.InjectMessage("DRIVE_COMMAND", bad);
  drive_command_t good{};
  good.mode = drive_command_t::VELOCITY;
  good.timeout = 0.5;
  bus.InjectMessage("DRIVE_COMMAND", good);
  EXPECT_NO_THROW(bus.HandleFor(0));
  EXPECT_EQ(bus.counters().messages_bad, 1);
  EXPECT_EQ(bus.counters().messages_in, 1);
}

// Issue 16, "absurd values": a finite but absurd pose or rate is refused in the decode path
// like a NaN, counted and never handed on (fuzz.contour_mapper.small found an ODOMETRY pose at
// y = 9e170 that made the mapper publish non-finite contour points).
TEST(TypedHelpers, AbsurdPosesAndRatesAreBadMessages) {
  FakeBus bus;
  std::vector<OdometryReading> accepted;
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t& m) { accepted.push_back(FromLcm(m)); });
  odometry_t far = MakeOdometry(10);
  far.pose.y = 9.49e170;
  odometry_t spun = MakeOdometry(20);
  spun.pose.theta = 5.76e228;
  odometry_t fast = MakeOdometry(30);
  fast.v = 7.5e199;
  odometry_t beyond = MakeOdometry(40);
  beyond.pose.x = -1.0000001e12;
  odometry_t large_but_sane = MakeOdometry(50);  // a UTM-sized position, many turns unwrapped
  large_but_sane.pose.x = 5.6e6;
  large_but_sane.pose.theta = 1000.0;
  large_but_sane.v = -12.0;
  for (const odometry_t& m : {far, spun, fast, beyond, large_but_sane}) bus.InjectMessage("ODOMETRY", m);
  EXPECT_NO_THROW(bus.HandleFor(0));
  EXPECT_EQ(bus.counters().messages_bad, 4);
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_EQ(accepted[0].utime, 50);
  try {
    FromLcm(far);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "odometry_t.pose is absurd (beyond 1e12 m or 1e6 rad)");
  }
  drive_command_t command{};
  command.mode = drive_command_t::VELOCITY;
  command.timeout = 0.5;
  command.omega = 2e3;
  EXPECT_THROW(FromLcm(command), InputError);
}

TEST(FakeBus, LoopbackDeliversOwnPublications) {
  FakeBus bus;
  bus.set_loopback(true);
  int n = 0;
  Subscribe<odometry_t>(bus, "ODOMETRY", [&](const odometry_t&) { ++n; });
  Publish(bus, "ODOMETRY", MakeOdometry(3));
  Publish(bus, "OTHER", MakeOdometry(4));
  EXPECT_EQ(bus.HandleFor(0), 2);
  EXPECT_EQ(n, 1);
  EXPECT_EQ(bus.Decoded<odometry_t>("OTHER").at(0).utime, 4);
}

}  // namespace
}  // namespace minenav
