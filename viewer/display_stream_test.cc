#include "viewer/display_stream.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/file_io.h"
#include "common/node/contour_map_conversions.h"
#include "common/node/conversions.h"
#include "minenav/heartbeat_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/pose_estimate_t.hpp"

namespace minenav {
namespace {

using nlohmann::json;

constexpr int64_t kT0 = 1'700'000'000'000'000;

template <typename T>
std::optional<DisplayMessage> Feed(DisplayStream& s, const std::string& channel, const T& m, int64_t at) {
  const std::vector<uint8_t> bytes = EncodeMessage(m);
  return s.OnMessage(channel, bytes.data(), bytes.size(), at);
}

ladar_scan_t Scan(int n) {
  ladar_scan_t m{};
  m.utime = kT0;
  m.scan_id = 7;
  m.sensor_id = "typhoon";
  m.start_angle = -3.0f;
  m.angle_step = static_cast<float>(2 * M_PI / n);
  m.min_range = 1.5f;
  m.max_range = 45.0f;
  m.num_ranges = n;
  for (int i = 0; i < n; ++i) m.ranges.push_back(2.0f + 0.01f * static_cast<float>(i % 100));
  m.ranges[0] = std::numeric_limits<float>::quiet_NaN();
  m.ranges[6] = 0.5f;  // below min_range: no return
  return m;
}

TEST(DisplayStreamTest, ScanIsDecimatedToAtMostMaxPointsAtTheOriginalBearings) {
  DisplayOptions o;
  o.max_scan_points = 360;
  DisplayStream s(o);
  const ladar_scan_t scan = Scan(2048);
  const auto d = Feed(s, "LADAR_SCAN", scan, kT0);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->schema_name, "minenav.viewer.scan");
  const json j = json::parse(d->payload);
  const int stride = j["stride"];
  EXPECT_EQ(stride, 6);  // ceil(2048 / 360)
  ASSERT_EQ(j["ranges"].size(), 342u);  // ceil(2048 / 6)
  EXPECT_LE(j["ranges"].size(), 360u);
  EXPECT_TRUE(j["ranges"][0].is_null());  // NaN
  EXPECT_TRUE(j["ranges"][1].is_null());  // reading 6: below the minimum range
  for (size_t k = 2; k < j["ranges"].size(); ++k) {
    // Reading k of the display is reading k * stride of the scan, at its bearing.
    const size_t i = k * static_cast<size_t>(stride);
    EXPECT_NEAR(j["ranges"][k].get<double>(), scan.ranges[i], 0.0005) << k;
    const double bearing = j["start_angle"].get<double>() + static_cast<double>(k) * j["angle_step"].get<double>();
    EXPECT_NEAR(bearing, scan.start_angle + static_cast<double>(i) * scan.angle_step, 1e-5);
  }
}

TEST(DisplayStreamTest, ScansAreSentAtMostMaxScanRateAndOtherChannelsAtMaxChannelRate) {
  DisplayOptions o;
  o.max_scan_rate = 5.0;
  o.max_channel_rate = 10.0;
  DisplayStream s(o);
  int scans = 0, poses = 0;
  for (int i = 0; i < 100; ++i) {  // 10 s of scans at 10 Hz
    if (Feed(s, "LADAR_SCAN", Scan(64), kT0 + i * 100'000)) ++scans;
  }
  pose_estimate_t p{};
  p.utime = kT0;
  p.source = "clue";
  for (int i = 0; i < 500; ++i)
    if (Feed(s, "POSE", p, kT0 + i * 20'000)) ++poses;  // 50 Hz for 10 s
  EXPECT_EQ(scans, 50);
  EXPECT_EQ(poses, 100);
  EXPECT_EQ(s.counters().throttled, 50 + 400);
}

TEST(DisplayStreamTest, PoseCarriesEveryFieldOfTheMessage) {
  DisplayStream s(DisplayOptions{});
  pose_estimate_t p{};
  p.utime = kT0 + 5;
  p.scan_id = 3;
  p.source = "clue";
  p.pose.x = 1.25;
  p.pose.y = -2.5;
  p.pose.theta = 0.5;
  p.covariance[0] = 0.01;
  p.covariance[4] = 0.04;
  p.converged = 1;
  p.status = "ok";
  const auto d = Feed(s, "POSE", p, kT0);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->schema_name, "minenav.pose_estimate_t");
  EXPECT_EQ(d->utime, kT0 + 5);
  const json j = json::parse(d->payload);
  EXPECT_EQ(j["pose"]["x"], 1.25);
  EXPECT_EQ(j["pose"]["y"], -2.5);
  EXPECT_EQ(j["covariance"].size(), 9u);
  EXPECT_EQ(j["covariance"][4], 0.04);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["source"], "clue");
  // The schema names every field the JSON has.
  const json schema = json::parse(d->schema);
  for (const auto& [key, value] : j.items()) EXPECT_TRUE(schema["properties"].contains(key)) << key;
}

TEST(DisplayStreamTest, CompressedContourMapIsInflatedAndSentOnlyWhenItsVersionChanges) {
  DisplayStream s(DisplayOptions{});
  ContourMapMessage map;
  map.utime = kT0;
  map.version = 4;
  map.num_scans = 12;
  for (int c = 0; c < 40; ++c) {
    ContourPolyline poly;
    poly.id = c;
    poly.closed = c % 2 == 0;
    for (int i = 0; i < 200; ++i) poly.points.emplace_back(c * 10.0 + i * 0.05, 3.0 + 0.001 * i);
    map.contours.push_back(poly);
  }
  const contour_map_t m = ContourMapToLcm(map);
  ASSERT_EQ(m.encoding, contour_map_t::ENCODING_ZLIB);
  const auto d = Feed(s, "CONTOUR_MAP", m, kT0);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->latched);
  const json j = json::parse(d->payload);
  EXPECT_EQ(j["version"], 4);
  ASSERT_EQ(j["contours"].size(), 40u);
  for (int c = 0; c < 40; ++c) {
    const json& jc = j["contours"][static_cast<size_t>(c)];
    EXPECT_EQ(jc["closed"], c % 2 == 0);
    ASSERT_EQ(jc["xy"].size(), 400u);
    for (int i = 0; i < 200; ++i) {
      EXPECT_NEAR(jc["xy"][static_cast<size_t>(2 * i)].get<double>(), map.contours[c].points[i].x(), 0.0006);
      EXPECT_NEAR(jc["xy"][static_cast<size_t>(2 * i + 1)].get<double>(), map.contours[c].points[i].y(), 0.0006);
    }
  }
  EXPECT_FALSE(Feed(s, "CONTOUR_MAP", m, kT0 + 1'000'000));  // same version: nothing
  map.version = 5;
  EXPECT_TRUE(Feed(s, "CONTOUR_MAP", ContourMapToLcm(map), kT0 + 2'000'000));
  EXPECT_EQ(s.counters().unchanged, 1);
}

TEST(DisplayStreamTest, WallsAreSentOncePerVersion) {
  DisplayStream s(DisplayOptions{});
  line_map_t w = SegmentsToLcm({Segment(0, 0, 10, 0)}, kT0, 1, "world 0");
  EXPECT_TRUE(Feed(s, "SIM_WORLD", w, kT0));
  EXPECT_FALSE(Feed(s, "SIM_WORLD", w, kT0 + 1));
  w.version = 2;
  const auto d = Feed(s, "SIM_WORLD", w, kT0 + 2);
  ASSERT_TRUE(d);
  EXPECT_TRUE(d->latched);
  EXPECT_EQ(json::parse(d->payload)["segments"][0]["x2"], 10.0);
}

TEST(DisplayStreamTest, FleetTableHasAgeStateAndRatesOfEachProcess) {
  DisplayOptions o;
  o.stale_after = 3.0;
  DisplayStream s(o);
  heartbeat_t h{};
  h.process = "contour_mapper";
  h.state = heartbeat_t::OK;
  h.message = "mapping";
  h.utime = kT0;
  h.messages_in = 100;
  h.messages_bad = 1;
  Feed(s, "HEARTBEAT", h, kT0);
  h.utime = kT0 + 2'000'000;  // 2 s later: 150 more in, 4 more bad
  h.messages_in = 250;
  h.messages_bad = 5;
  Feed(s, "HEARTBEAT", h, kT0 + 2'000'000);
  heartbeat_t other = h;
  other.process = "vehicle_sim";
  other.state = heartbeat_t::WARN;
  Feed(s, "HEARTBEAT", other, kT0);  // only one heartbeat: no rate yet

  const json j = json::parse(s.FleetTable(kT0 + 2'500'000).payload);
  ASSERT_EQ(j["processes"].size(), 2u);
  const json& mapper = j["processes"][0];
  EXPECT_EQ(mapper["process"], "contour_mapper");
  EXPECT_EQ(mapper["state"], "OK");
  EXPECT_DOUBLE_EQ(mapper["age_s"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(mapper["in_rate_hz"].get<double>(), 75.0);
  EXPECT_DOUBLE_EQ(mapper["bad_rate_hz"].get<double>(), 2.0);
  EXPECT_EQ(mapper["stale"], false);
  const json& sim = j["processes"][1];
  EXPECT_EQ(sim["state"], "WARN");
  EXPECT_TRUE(sim["in_rate_hz"].is_null());
  EXPECT_DOUBLE_EQ(sim["age_s"].get<double>(), 2.5);
  EXPECT_EQ(json::parse(s.FleetTable(kT0 + 3'100'000).payload)["processes"][1]["stale"], true);
}

TEST(DisplayStreamTest, BadPayloadsThrowOneLineAndForeignChannelsAreIgnored) {
  DisplayStream s(DisplayOptions{});
  std::vector<uint8_t> bytes = EncodeMessage(Scan(100));
  bytes.resize(bytes.size() / 2);  // truncated
  try {
    s.OnMessage("LADAR_SCAN", bytes.data(), bytes.size(), kT0);
    FAIL() << "a truncated scan was shown";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("LADAR_SCAN"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
  const std::vector<uint8_t> foreign = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_FALSE(s.OnMessage("SOMEONE_ELSES", foreign.data(), foreign.size(), kT0));
  EXPECT_EQ(s.counters().foreign, 1);
  // A wrong type on a channel the design names is bad, not foreign.
  const std::vector<uint8_t> pose = EncodeMessage(pose_estimate_t{});
  EXPECT_THROW(s.OnMessage("LADAR_SCAN", pose.data(), pose.size(), kT0), InputError);
  // Invalid UTF-8 in a string field still makes valid JSON.
  heartbeat_t h{};
  h.process = "bad\xff\xfe";
  const auto d = Feed(s, "HEARTBEAT", h, kT0);
  ASSERT_TRUE(d);
  EXPECT_NO_THROW(json::parse(d->payload));
  EXPECT_NO_THROW(json::parse(s.FleetTable(kT0).payload));
}

}  // namespace
}  // namespace minenav

namespace minenav {
namespace {

TEST(DisplayStreamTest, FoxgloveSchemasBesideTheShownMessages) {
  DisplayStream s(DisplayOptions{});
  pose_estimate_t p{};
  p.utime = kT0;
  p.pose.x = 10.0;
  p.pose.y = 5.0;
  p.pose.theta = M_PI / 2;
  std::vector<uint8_t> bytes = EncodeMessage(p);
  const auto poses = s.OnMessageWithFoxglove("POSE", bytes.data(), bytes.size(), kT0);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[1].topic, "/foxglove/POSE");
  EXPECT_EQ(poses[1].schema_name, "foxglove.PoseInFrame");
  const json fp = json::parse(poses[1].payload);
  EXPECT_EQ(fp["frame_id"], "map");
  EXPECT_NEAR(fp["pose"]["orientation"]["z"].get<double>(), std::sin(M_PI / 4), 1e-12);
  EXPECT_NEAR(fp["pose"]["orientation"]["w"].get<double>(), std::cos(M_PI / 4), 1e-12);

  ladar_scan_t scan = Scan(2048);
  scan.sensor_offset.x = 1.0;  // 1 m ahead of the vehicle: at (10, 6) when facing +y
  bytes = EncodeMessage(scan);
  const auto scans = s.OnMessageWithFoxglove("LADAR_SCAN", bytes.data(), bytes.size(), kT0);
  ASSERT_EQ(scans.size(), 2u);
  const json page = json::parse(scans[0].payload), fox = json::parse(scans[1].payload);
  EXPECT_EQ(scans[1].schema_name, "foxglove.LaserScan");
  EXPECT_EQ(fox["ranges"].size(), page["ranges"].size());  // the same decimated readings
  EXPECT_NEAR(fox["pose"]["position"]["x"].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(fox["pose"]["position"]["y"].get<double>(), 6.0, 1e-9);
  EXPECT_NEAR(fox["end_angle"].get<double>() - fox["start_angle"].get<double>(),
              (static_cast<double>(page["ranges"].size()) - 1) * page["angle_step"].get<double>(), 1e-6);
  // A throttled message has no Foxglove twin either.
  EXPECT_TRUE(s.OnMessageWithFoxglove("LADAR_SCAN", bytes.data(), bytes.size(), kT0 + 1).empty());
}

}  // namespace
}  // namespace minenav
