// info / export / render on small logs built inline, and damaged logs.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "common/message_auth.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "logger/log_render.h"
#include "logger/log_summary.h"
#include "logger/message_catalog.h"
#include "minenav/cutter_command_t.hpp"
#include "minenav/drive_command_t.hpp"
#include "minenav/message_json.hpp"
#include "logger/run_log.h"
#include "logger/strict_log_reader.h"
#include "logger/test_logs.h"

namespace minenav {
namespace {

using logger_test::MakeTestRun;
using logger_test::TempPath;
using logger_test::WriteTestLog;

const ChannelSummary* Find(const LogSummary& s, const std::string& channel) {
  for (const auto& c : s.channels)
    if (c.channel == channel) return &c;
  return nullptr;
}

TEST(MessageCatalog, ChannelsMapToTheirTypes) {
  EXPECT_EQ(ExpectedTypeForChannel("LADAR_SCAN"), "minenav.ladar_scan_t");
  EXPECT_EQ(ExpectedTypeForChannel("LADAR_SCAN_FRONT"), "minenav.ladar_scan_t");
  EXPECT_EQ(ExpectedTypeForChannel("POSE"), "minenav.pose_estimate_t");
  EXPECT_EQ(ExpectedTypeForChannel("POSE_IPE"), "minenav.pose_estimate_t");
  EXPECT_EQ(ExpectedTypeForChannel("PATH_REQUEST"), "minenav.path_request_t");
  EXPECT_EQ(ExpectedTypeForChannel("PATH"), "minenav.path_t");
  EXPECT_EQ(ExpectedTypeForChannel("PATHOLOGY"), "");
  EXPECT_EQ(ExpectedTypeForChannel("SIM_WORLD"), "minenav.line_map_t");
  EXPECT_EQ(ExpectedTypeForChannel("SOMETHING_ELSE"), "");
  EXPECT_EQ(ExpectedTypeForChannel("DRIVE_PATH"), "minenav.path_t");
  EXPECT_EQ(ExpectedTypeForChannel("CUT_TASK"), "minenav.cutter_command_t");
  EXPECT_EQ(ExpectedTypeForChannel("TASK_REQUEST"), "minenav.task_request_t");
  EXPECT_EQ(KnownMessageTypes().size(), 17u);  // every top-level type of lcmtypes/ but the nested ones
}

// Issue 17: every known type decodes to JSON whose fields are exactly its schema's properties.
TEST(MessageCatalog, EveryTypeHasItsJsonFormAndSchema) {
  int checked = 0;
  ForEachMessageType([&]<typename T>() {
    const KnownMessageType* type = FindKnownTypeByName(std::string("minenav.") + T::getTypeName());
    if (type == nullptr) return;  // nested types (pose2d_t, contour_t, ...) travel inside others
    const std::vector<uint8_t> bytes = EncodeMessage(T{});
    nlohmann::json j;
    std::string error;
    ASSERT_TRUE(type->to_json(bytes.data(), bytes.size(), &j, &error)) << type->name << ": " << error;
    const nlohmann::json schema = nlohmann::json::parse(type->json_schema);
    EXPECT_EQ(schema["title"], type->name);
    for (const auto& [key, value] : j.items()) EXPECT_TRUE(schema["properties"].contains(key)) << type->name << "." << key;
    for (const auto& key : schema["required"]) EXPECT_TRUE(j.contains(key.get<std::string>())) << type->name << "." << key;
    std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 1);
    EXPECT_FALSE(type->to_json(cut.data(), cut.size(), &j, &error)) << type->name << ": a truncated payload";
    ++checked;
  });
  EXPECT_EQ(checked, static_cast<int>(KnownMessageTypes().size()));
}

TEST(MessageCatalog, ProbeTellsWrongTypeTruncationAndForeignApart) {
  OdometryReading o;
  o.utime = 42;
  o.seq = 7;
  const auto odo = EncodeMessage(ToLcm(o));
  const MessageProbe good = ProbeMessage("ODOMETRY", odo.data(), odo.size());
  ASSERT_TRUE(good.ok) << good.error;
  EXPECT_EQ(good.type_name, "minenav.odometry_t");
  EXPECT_EQ(*good.utime, 42);
  EXPECT_EQ(*good.sequence, 7);
  EXPECT_EQ(good.sequence_field, "seq");

  const MessageProbe wrong = ProbeMessage("LADAR_SCAN", odo.data(), odo.size());
  EXPECT_FALSE(wrong.ok);
  EXPECT_NE(wrong.error.find("is not minenav.ladar_scan_t's"), std::string::npos) << wrong.error;
  EXPECT_NE(wrong.error.find("it is minenav.odometry_t"), std::string::npos) << wrong.error;

  const MessageProbe cut = ProbeMessage("ODOMETRY", odo.data(), odo.size() - 5);
  EXPECT_FALSE(cut.ok);
  EXPECT_NE(cut.error.find("truncated"), std::string::npos) << cut.error;

  std::vector<uint8_t> longer = odo;
  longer.push_back(0);
  const MessageProbe extra = ProbeMessage("ODOMETRY", longer.data(), longer.size());
  EXPECT_FALSE(extra.ok);
  EXPECT_NE(extra.error.find("left over"), std::string::npos) << extra.error;

  const MessageProbe tiny = ProbeMessage("ODOMETRY", odo.data(), 3);
  EXPECT_FALSE(tiny.ok);

  // An unknown channel with a minenav type is decoded by fingerprint; a foreign type is fine.
  const MessageProbe by_fp = ProbeMessage("MY_ODO", odo.data(), odo.size());
  EXPECT_TRUE(by_fp.ok);
  EXPECT_EQ(by_fp.type_name, "minenav.odometry_t");
  const std::vector<uint8_t> foreign(20, 0xAB);
  const MessageProbe other = ProbeMessage("MY_THING", foreign.data(), foreign.size());
  EXPECT_TRUE(other.ok);
  EXPECT_FALSE(other.known_type);
}

TEST(StrictLogReader, ReadsTheSameEventsAsTheNodeRuntimeReader) {
  const std::string path = TempPath("run.lcm");
  WriteTestLog(path, MakeTestRun(4, 90));
  StrictLogReader strict(path);
  LogReader lcm_reader(path);
  LogRecord rec;
  int n = 0;
  while (strict.Next(&rec)) {
    const auto e = lcm_reader.Next();
    ASSERT_TRUE(e.has_value());
    EXPECT_EQ(rec.channel, e->channel);
    EXPECT_EQ(rec.timestamp, e->timestamp);
    EXPECT_EQ(rec.eventnum, e->eventnum);
    EXPECT_EQ(rec.data, e->data);
    ++n;
  }
  EXPECT_FALSE(lcm_reader.Next().has_value());
  EXPECT_EQ(n, 16);
  EXPECT_EQ(strict.position(), strict.file_size());
}

TEST(LogSummary, CountsRatesTimesAndTypes) {
  const std::string path = TempPath("run.lcm");
  const auto run = MakeTestRun(5, 180);
  WriteTestLog(path, run);
  const LogSummary s = SummarizeLog(path);
  EXPECT_EQ(s.events, 20);
  EXPECT_TRUE(s.file_error.empty());
  EXPECT_EQ(s.total_decode_errors(), 0);
  ASSERT_EQ(s.channels.size(), 4u);
  const ChannelSummary* scans = Find(s, "LADAR_SCAN");
  ASSERT_NE(scans, nullptr);
  EXPECT_EQ(scans->type, "minenav.ladar_scan_t");
  EXPECT_EQ(scans->count, 5);
  EXPECT_NEAR(scans->rate_hz, 1.0, 1e-9);  // stations 1 s apart
  EXPECT_EQ(*scans->first_utime, run.scans.front().utime);
  EXPECT_EQ(*scans->last_utime, run.scans.back().utime);
  EXPECT_EQ(scans->sequence_field, "scan_id");
  EXPECT_EQ(scans->sequence_gaps, 0);
  EXPECT_EQ(scans->bytes, 5 * static_cast<int64_t>(EncodeMessage(ToLcm(run.scans[0])).size()));
  const ChannelSummary* pose = Find(s, "POSE_IPE");
  ASSERT_NE(pose, nullptr);
  EXPECT_EQ(pose->type, "minenav.pose_estimate_t");
  EXPECT_EQ(pose->first_timestamp, run.scans.front().utime + 50'000);
  EXPECT_EQ(Find(s, "ODOMETRY")->sequence_field, "seq");

  const std::string table = FormatLogSummary(s);
  EXPECT_NE(table.find("LADAR_SCAN"), std::string::npos);
  EXPECT_NE(table.find("minenav.vehicle_truth_t"), std::string::npos);
  const std::string json = LogSummaryToJson(s);
  EXPECT_NE(json.find("\"count\": 5"), std::string::npos);
}

TEST(LogSummary, FindsGapsInScanIdsAndSeq) {
  const std::string path = TempPath("gaps.lcm");
  auto run = MakeTestRun(6, 36);
  {
    LogWriter w(path);
    const int ids[] = {0, 1, 3, 4, 8, 8};  // 2 jumps skipping 1 + 3, one repeat
    for (int k = 0; k < 6; ++k) {
      run.scans[static_cast<size_t>(k)].scan_id = ids[k];
      w.WriteMessage("LADAR_SCAN", run.scans[static_cast<size_t>(k)].utime, ToLcm(run.scans[static_cast<size_t>(k)]));
    }
    w.Close();
  }
  const LogSummary s = SummarizeLog(path);
  const ChannelSummary* c = Find(s, "LADAR_SCAN");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->sequence_gaps, 2);
  EXPECT_EQ(c->missing, 4);
  EXPECT_EQ(c->out_of_order, 1);
  EXPECT_EQ(*c->first_sequence, 0);
  EXPECT_EQ(*c->last_sequence, 8);
}

// Two publishers on one channel, each numbering its own commands (the tracker and the cutter
// on DRIVE_COMMAND), a channel whose seq is not a per-channel counter (CUT_TASK: the
// coordinator's task ids) and one lost command: the loss is found, once, and the interleaving
// is not taken for disorder.
TEST(LogSummary, FollowsEachSendersSequenceOnASharedChannel) {
  const std::string path = TempPath("signed.lcm");
  const AuthKeyRing keys{{RandomAuthKey(7)}};
  MessageSigner tracker(0x1111), cutter(0x2222), coordinator(0x3333);
  auto drive = [](int64_t seq) {
    minenav::drive_command_t m{};
    m.utime = 1000 + seq;
    m.seq = seq;
    m.timeout = 0.5;
    return EncodeMessage(m);
  };
  auto cut = [](int64_t task_id) {
    minenav::cutter_command_t m{};
    m.utime = 5000 + task_id;
    m.seq = task_id;
    return EncodeMessage(m);
  };
  {
    LogWriter w(path);
    int64_t t = 1;
    auto write = [&](MessageSigner* signer, const std::string& channel, const std::vector<uint8_t>& payload) {
      const auto bytes = signer ? signer->Sign(keys, channel, payload.data(), static_cast<int>(payload.size()), t)
                                : payload;
      w.Write(channel, t++, bytes.data(), static_cast<int>(bytes.size()));
    };
    for (int64_t k = 0; k < 10; ++k) {
      const auto from_tracker = drive(k);
      if (k == 6) {  // signed, then lost: the tracker's trailer and its seq skip one
        tracker.Sign(keys, "DRIVE_COMMAND", from_tracker.data(), static_cast<int>(from_tracker.size()), t);
      } else {
        write(&tracker, "DRIVE_COMMAND", from_tracker);
      }
      if (k >= 3 && k < 7) write(&cutter, "DRIVE_COMMAND", drive(k - 3));  // its own 0..3
    }
    for (const int64_t task : {4, 9, 15}) write(&coordinator, "CUT_TASK", cut(task));
    write(nullptr, "DRIVE_COMMAND", drive(0));  // an unsigned publisher: a sequence of its own
    w.Close();
  }
  const LogSummary s = SummarizeLog(path);
  const ChannelSummary* d = Find(s, "DRIVE_COMMAND");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->count, 9 + 4 + 1);
  EXPECT_EQ(d->signed_senders, 2);
  EXPECT_EQ(d->unsigned_count, 1);
  EXPECT_EQ(d->sequence_gaps, 1);
  EXPECT_EQ(d->missing, 1);
  EXPECT_EQ(d->out_of_order, 0);  // by one sequence it would be 6 (every switch of publisher)

  ASSERT_EQ(s.senders.size(), 3u);  // by first appearance
  EXPECT_EQ(s.senders[0].sender, 0x1111u);
  EXPECT_EQ(s.senders[0].count, 9);
  EXPECT_EQ(*s.senders[0].trailer_seq.first, 1);
  EXPECT_EQ(*s.senders[0].trailer_seq.last, 10);
  EXPECT_EQ(s.senders[0].trailer_seq.missing, 1);
  EXPECT_EQ(s.senders[1].sender, 0x2222u);
  EXPECT_EQ(s.senders[1].trailer_seq.gaps, 0);
  EXPECT_EQ(s.senders[1].channels, std::vector<std::string>{"DRIVE_COMMAND"});
  // CUT_TASK's seq jumps by design; its sender's trailer does not: nothing lost there.
  EXPECT_EQ(Find(s, "CUT_TASK")->missing, 9 - 4 - 1 + 15 - 9 - 1);
  EXPECT_EQ(s.senders[2].count, 3);
  EXPECT_EQ(s.senders[2].trailer_seq.gaps, 0);
  EXPECT_EQ(s.senders[2].channels, std::vector<std::string>{"CUT_TASK"});

  const std::string table = FormatLogSummary(s);
  EXPECT_TRUE(std::regex_search(table, std::regex("0000000000001111 +9 +1 \\.\\. 10 +1 +1 +0 +DRIVE_COMMAND\n")))
      << table;
  EXPECT_NE(table.find("(3 publishers, each its own sequence)"), std::string::npos) << table;
  const std::string json = LogSummaryToJson(s);
  EXPECT_NE(json.find("\"sender\": \"0000000000003333\""), std::string::npos) << json;
}

TEST(LogSummary, ReportsDecodeErrorsPerChannel) {
  const std::string path = TempPath("bad.lcm");
  const auto run = MakeTestRun(3, 36);
  {
    LogWriter w(path);
    const auto scan = EncodeMessage(ToLcm(run.scans[0]));
    w.Write("LADAR_SCAN", 1, scan.data(), static_cast<int>(scan.size()));
    w.Write("LADAR_SCAN", 2, scan.data(), static_cast<int>(scan.size()) - 10);  // truncated
    TruthReading t;
    const auto truth = EncodeMessage(ToLcm(t));
    w.Write("ODOMETRY", 3, truth.data(), static_cast<int>(truth.size()));  // wrong type
    w.Close();
  }
  const LogSummary s = SummarizeLog(path);
  EXPECT_TRUE(s.file_error.empty());
  EXPECT_EQ(s.total_decode_errors(), 2);
  EXPECT_EQ(Find(s, "LADAR_SCAN")->count, 2);
  EXPECT_EQ(Find(s, "LADAR_SCAN")->decode_errors, 1);
  EXPECT_NE(Find(s, "LADAR_SCAN")->first_error.find("truncated"), std::string::npos);
  EXPECT_NE(Find(s, "ODOMETRY")->first_error.find("it is minenav.vehicle_truth_t"), std::string::npos);
  EXPECT_NE(FormatLogSummary(s).find("decode errors: 1 on ODOMETRY"), std::string::npos);
}

TEST(LogSummary, ReportsADamagedFileWithTheByteOffset) {
  const std::string path = TempPath("cut.lcm");
  WriteTestLog(path, MakeTestRun(3, 36));
  const auto size = std::filesystem::file_size(path);
  // Cut inside the last event: the summary covers what came before and names the damage.
  std::filesystem::resize_file(path, size - 7);
  const LogSummary cut = SummarizeLog(path);
  EXPECT_EQ(cut.events, 11);
  EXPECT_NE(cut.file_error.find("truncated event"), std::string::npos) << cut.file_error;

  // Garbage in the middle: LCM's own reader would skip it silently.
  std::string bytes = logger_test::ReadAll(path);
  StrictLogReader first(path);
  LogRecord rec;
  ASSERT_TRUE(first.Next(&rec));
  const int64_t second_event = first.position();
  bytes[static_cast<size_t>(second_event)] = 0x00;
  const std::string bad = TempPath("garbage.lcm");
  std::ofstream(bad, std::ios::binary) << bytes;
  const LogSummary g = SummarizeLog(bad);
  EXPECT_EQ(g.events, 1);
  EXPECT_NE(g.file_error.find("bad magic"), std::string::npos) << g.file_error;
  EXPECT_NE(g.file_error.find("byte " + std::to_string(second_event)), std::string::npos) << g.file_error;
}

TEST(RunLog, ReadsTracksAndScansAndRejectsBadMessages) {
  const std::string path = TempPath("run.lcm");
  const auto run = MakeTestRun(5, 72);
  WriteTestLog(path, run);
  const RunLog r = ReadRunLog(path);
  ASSERT_EQ(r.tracks.size(), 3u);
  ASSERT_EQ(r.tracks.at("SIM_TRUTH").poses.size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(r.tracks.at("SIM_TRUTH").poses[k].utime, run.truth[k].utime);
    EXPECT_NEAR(r.tracks.at("SIM_TRUTH").poses[k].pose.x, run.truth[k].pose.x, 1e-12);
    EXPECT_NEAR(r.tracks.at("ODOMETRY").poses[k].pose.y, run.odometry[k].pose.y, 1e-12);
    EXPECT_NEAR(r.tracks.at("POSE_IPE").poses[k].pose.theta, run.estimates[k].pose.theta, 1e-12);
  }
  ASSERT_EQ(r.scans.at("LADAR_SCAN").size(), 5u);
  EXPECT_EQ(r.scans.at("LADAR_SCAN")[2].ranges, run.scans[2].ranges);

  const std::string bad = TempPath("bad.lcm");
  {
    LogWriter w(bad);
    const auto scan = EncodeMessage(ToLcm(run.scans[0]));
    w.Write("LADAR_SCAN", 1, scan.data(), static_cast<int>(scan.size()) - 1);
    w.Close();
  }
  try {
    ReadRunLog(bad);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("channel LADAR_SCAN"), std::string::npos) << what;
    EXPECT_NE(what.find("byte 0"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(RunLog, PoseAtMatchesExactlyAndInterpolates) {
  const std::vector<StampedPose> poses = {{0, Pose2(0, 0, 3.0)}, {100, Pose2(1, 2, -3.0)}, {1000, Pose2(5, 5, 0)}};
  EXPECT_NEAR(PoseAt(poses, 100, 50)->x, 1.0, 1e-12);
  const auto mid = PoseAt(poses, 50, 200);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->x, 0.5, 1e-12);
  EXPECT_NEAR(mid->y, 1.0, 1e-12);
  // 3.0 -> -3.0 goes the short way through pi.
  EXPECT_NEAR(std::abs(mid->theta), kPi, 1e-9);
  EXPECT_FALSE(PoseAt(poses, 500, 200).has_value());  // gap of 900 us > 200
  EXPECT_FALSE(PoseAt(poses, -5, 1000).has_value());
  EXPECT_FALSE(PoseAt(poses, 2000, 1000).has_value());
}

TEST(RunLog, ScansCsvHasOneRowPerReading) {
  const auto run = MakeTestRun(2, 10);
  const std::string csv = ScansToCsv(run.scans, false);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "utime,scan_id,index,bearing,range");
  int rows = 0;
  while (std::getline(in, line)) {
    long long utime = 0, id = 0, index = 0;
    double bearing = 0, range = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lld,%lld,%lld,%lf,%lf", &utime, &id, &index, &bearing, &range), 5) << line;
    const auto& scan = run.scans[static_cast<size_t>(id)];
    EXPECT_EQ(utime, scan.utime);
    EXPECT_NEAR(bearing, scan.Bearing(static_cast<size_t>(index)), 1e-6);
    EXPECT_NEAR(range, scan.ranges[static_cast<size_t>(index)], 1e-5);
    ++rows;
  }
  EXPECT_EQ(rows, 20);
}

TEST(LogRender, ScanPointsAtTruthLieOnTheWallsAndTheSvgHasEveryLayer) {
  const std::string path = TempPath("run.lcm");
  const auto run = MakeTestRun(5, 360);
  WriteTestLog(path, run);
  const std::string world = TempPath("world.json");
  SaveSegmentsJson(world, run.world);
  LogRenderOptions options;
  options.world_paths = {world};
  options.scans_at_odometry = true;
  options.max_points_per_scan = 0;
  const LogRenderResult result = BuildLogScene(path, options);
  EXPECT_EQ(result.scans_drawn, 5);
  EXPECT_EQ(result.scans_without_pose, 0);
  ASSERT_EQ(result.scene.points.size(), 2u);
  const SvgPointLayer& at_truth = result.scene.points[0];
  EXPECT_EQ(at_truth.points.size(), 5u * 360u);
  double worst = 0;
  for (const auto& p : at_truth.points) {
    double d = 1e9;
    for (const auto& s : run.world) d = std::min(d, PointToSegmentDistance(p, s));
    worst = std::max(worst, d);
  }
  EXPECT_LT(worst, 1e-5);  // float ranges, exact ray casting
  // At odometry poses (0.2 m off) the points are visibly off the walls.
  double mean_off = 0;
  for (const auto& p : result.scene.points[1].points) {
    double d = 1e9;
    for (const auto& s : run.world) d = std::min(d, PointToSegmentDistance(p, s));
    mean_off += d;
  }
  mean_off /= static_cast<double>(result.scene.points[1].points.size());
  EXPECT_GT(mean_off, 0.05);

  ASSERT_EQ(result.scene.trajectories.size(), 3u);  // ODOMETRY, POSE_IPE, SIM_TRUTH (on top)
  EXPECT_EQ(result.scene.trajectories.back().label, "SIM_TRUTH (5)");
  ASSERT_EQ(result.scene.links.size(), 1u);
  EXPECT_EQ(result.scene.links[0].links.size(), 5u);

  const std::string svg = RenderSvg(result.scene);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  for (const char* label : {"world walls", "scan points at SIM_TRUTH poses", "SIM_TRUTH (5)", "ODOMETRY (5)",
                            "POSE_IPE (5)", "Legend", "(grid spacing)"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  // One dot per point of both layers.
  const std::regex dot("h0");
  const auto dots = std::distance(std::sregex_iterator(svg.begin(), svg.end(), dot), std::sregex_iterator());
  EXPECT_EQ(static_cast<size_t>(dots), result.scene.points[0].points.size() + result.scene.points[1].points.size());
}

TEST(LogRender, StridesScansAndDrawsContourMaps) {
  const std::string path = TempPath("run.lcm");
  WriteTestLog(path, MakeTestRun(2, 360));
  const std::string map = TempPath("map.json");
  std::ofstream(map) << R"({"contours": [{"closed": true, "points": [[0,0],[1,0],[1,1]]}, {"points": [[2,2],[3,3]]}]})";
  LogRenderOptions options;
  options.map_path = map;
  options.max_points_per_scan = 90;
  const LogRenderResult r = BuildLogScene(path, options);
  ASSERT_EQ(r.scene.lines.size(), 1u);
  EXPECT_EQ(r.scene.lines[0].polylines.size(), 2u);
  EXPECT_TRUE(r.scene.lines[0].polylines[0].closed);
  EXPECT_EQ(r.scene.points[0].points.size(), 2u * 90u);

  options.max_scans = 1;  // the first scan only
  EXPECT_EQ(BuildLogScene(path, options).scene.points[0].points.size(), 90u);
  options.max_scans = 200;

  options.scans_at = "POSE_NOPE";
  EXPECT_THROW(BuildLogScene(path, options), InputError);
  std::ofstream(map) << R"({"contours": [{"points": [[0,0],[1]]}]})";
  options.scans_at = "auto";
  EXPECT_THROW(BuildLogScene(path, options), InputError);
}

TEST(SvgRender, NiceLengths) {
  EXPECT_DOUBLE_EQ(NiceLength(0.9), 1.0);
  EXPECT_DOUBLE_EQ(NiceLength(2.7), 2.0);
  EXPECT_DOUBLE_EQ(NiceLength(4.0), 5.0);
  EXPECT_DOUBLE_EQ(NiceLength(8.0), 10.0);
  EXPECT_DOUBLE_EQ(NiceLength(13.0), 10.0);
  EXPECT_DOUBLE_EQ(NiceLength(0.031), 0.02);
}

}  // namespace
}  // namespace minenav
