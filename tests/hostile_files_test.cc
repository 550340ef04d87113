// Issue 11, hostile files: logs holding payloads whose counts lie, event headers that lie
// and corrupt bytes, read by `contour_mapper --log`, `log_tool info` and `log_tool
// render`, each run under a memory bound with its peak RSS measured
// (tests/limited_process.h). No bus.
//
// The logs are written byte by byte (tests/hostile_messages.h RawLog): a survey of 20
// scans in a small room, each with an ODOMETRY reading of the same utime (the scan's
// initial estimate), 0.35 m apart.
//   * item 1: the 92-byte scan with num_ranges (or num_intensities) = 2^29 in the middle:
//     no tool may crash (unfixed all three exit 139); exit 0 or 2, peak RSS < 300 MB, the
//     bad message named;
//   * item 10: a negative count or a huge num_contours: `log_tool info` reports the
//     message as bad (channel and byte offset) and exits 0 or 2 (unfixed: exit 3
//     "vector::_M_default_append" or bad_alloc, or 1-2 GiB zero-filled first);
//   * item 8: an event header with datalen 0x7fffffff: contour_mapper exits 0 (log cut
//     short, named) or 2 (damage named with its offset), never inside liblcm (unfixed: 139);
//   * item 9: 64 corrupt bytes over an event header at 20 % of the log: an error (non-zero
//     exit, one line naming the file and the byte offset), never a silent success
//     (unfixed: the reader skips to the next magic number and the run exits 0).

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "common/file_io.h"
#include "common/node/conversions.h"
#include "common/node/event_log.h"
#include "mapper/test_world.h"
#include "minenav/contour_map_t.hpp"
#include "minenav/ladar_scan_t.hpp"
#include "minenav/line_map_t.hpp"
#include "minenav/odometry_t.hpp"
#include "tests/hostile_messages.h"
#include "tests/temp_dir.h"
#include "tests/limited_process.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;
using testing::DescribeExit;
using testing::kMaxPeakRssKb;
using testing::kSlowdown;
using testing::ProcessResult;
using testing::RawLog;
using testing::RunLimited;

constexpr int kScans = 20;
constexpr int64_t kT0 = 1'700'000'000'000'000;  // us, 2023-11-14


// Lines of `text` that contain every one of `needles`.
std::vector<std::string> LinesWith(const std::string& text, const std::vector<std::string>& needles) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    bool all = true;
    for (const std::string& n : needles) all = all && line.find(n) != std::string::npos;
    if (all && !line.empty()) out.push_back(line);
    start = end + 1;
  }
  return out;
}

std::string Tail(const std::string& text, size_t n = 3000) {
  return text.size() <= n ? text : "..." + text.substr(text.size() - n);
}

// The survey as a RawLog: per station ODOMETRY then LADAR_SCAN with the same utime
// (event timestamps = utimes, increasing); `before_station(log, k)` may add events before
// station k's, stamped between station k-1 and k.
RawLog Survey(const std::function<void(RawLog&, int)>& before_station = nullptr) {
  RawLog log;
  mapper::testing::ScanSpec spec;
  spec.range_sigma = 0.01;
  for (int k = 0; k < kScans; ++k) {
    const Pose2 pose(3.0 + 0.35 * k, 9.0, 0.0);
    const int64_t utime = kT0 + int64_t{k} * 1'000'000;
    if (before_station) before_station(log, k);
    OdometryReading o;
    o.utime = utime;
    o.seq = k;
    o.pose = pose;
    log.AddMessage("ODOMETRY", ToLcm(o));
    spec.seed = static_cast<unsigned>(k + 1);
    LadarScan scan = mapper::testing::MakeScan(mapper::testing::SmallRoomWorld(), pose, spec);
    scan.utime = utime;
    scan.scan_id = k;
    scan.sensor_id = "typhoon";
    log.AddMessage("LADAR_SCAN", ToLcm(scan));
  }
  return log;
}

class HostileFilesTest : public ::testing::Test {
 protected:
  ProcessResult Mapper(const std::string& log, const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv = {MINENAV_CONTOUR_MAPPER_BIN, "--log", log, "--map-out", dir_ / "map.json",
                                     "--poses-out", dir_ / "poses.csv", "--final-refinement-rounds", "0"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return RunLimited(argv, dir_ / "mapper.txt", 60.0 * kSlowdown);
  }
  ProcessResult Info(const std::string& log) {
    return RunLimited({MINENAV_LOG_TOOL_BIN, "info", log}, dir_ / "info.txt", 60.0 * kSlowdown);
  }
  ProcessResult Render(const std::string& log) {
    return RunLimited({MINENAV_LOG_TOOL_BIN, "render", log, "--out", dir_ / "render.svg"}, dir_ / "render.txt",
                      60.0 * kSlowdown);
  }

  testing::TempDir dir_{"minenav_hostile_files"};
};

// One line on stdout per run: how it ended, its peak RSS and its last line, so a log of
// a passing run still shows what the fixed code said.
void Summarize(const ProcessResult& r, const std::string& what) {
  std::string last = r.output;
  while (!last.empty() && (last.back() == '\n' || last.back() == ' ')) last.pop_back();
  last = last.substr(last.find_last_of("\n\r") == std::string::npos ? 0 : last.find_last_of("\n\r") + 1);
  std::cout << "[   info   ] " << what << ": " << DescribeExit(r.exit_code) << ", peak RSS " << r.peak_rss_kb / 1024
            << " MB; last line: " << last.substr(0, 300) << std::endl;
}

// Exit 0 or 2 (never a crash, never exit 3) and a peak RSS under the bound.
void ExpectNoCrashAndBounded(const ProcessResult& r, const std::string& what) {
  Summarize(r, what);
  EXPECT_TRUE(r.exit_code && (*r.exit_code == 0 || *r.exit_code == 2))
      << what << ": " << DescribeExit(r.exit_code) << "; expected exit 0 (bad message counted) or 2 (bad input "
      << "file, one line)\n"
      << Tail(r.output);
  EXPECT_LT(r.peak_rss_kb, kMaxPeakRssKb) << what << ": peak RSS " << r.peak_rss_kb / 1024 << " MB (bound "
                                          << kMaxPeakRssKb / 1024 << " MB)";
  for (const char* leak : {"bad_alloc", "_M_default_append", "length_error"})
    EXPECT_EQ(r.output.find(leak), std::string::npos) << what << ": an allocation failure escaped (" << leak
                                                      << ")\n"
                                                      << Tail(r.output);
}

// The control: the clean survey maps every scan, and the tools read it, well under the
// memory bound (so the bound is not what fails the other tests).
TEST_F(HostileFilesTest, TheCleanSurveyIsReadAndMappedCompletely) {
  const std::string log = dir_ / "clean.lcm";
  Survey().Save(log);
  const ProcessResult m = Mapper(log);
  ASSERT_EQ(m.exit_code, 0) << DescribeExit(m.exit_code) << "\n" << Tail(m.output);
  EXPECT_EQ(LoadPosesCsv(dir_ / "poses.csv").size(), static_cast<size_t>(kScans)) << Tail(m.output);
  EXPECT_LT(m.peak_rss_kb, kMaxPeakRssKb) << "contour_mapper on a clean log: peak RSS " << m.peak_rss_kb / 1024 << " MB";
  const ProcessResult i = Info(log);
  EXPECT_EQ(i.exit_code, 0) << DescribeExit(i.exit_code) << "\n" << Tail(i.output);
  EXPECT_LT(i.peak_rss_kb, kMaxPeakRssKb);
  const ProcessResult r = Render(log);
  EXPECT_EQ(r.exit_code, 0) << DescribeExit(r.exit_code) << "\n" << Tail(r.output);
  EXPECT_LT(r.peak_rss_kb, kMaxPeakRssKb);
  // The LogWriter of the project reads the same events back from a RawLog.
  LogReader reader(log);
  int events = 0;
  while (reader.Next()) ++events;
  EXPECT_EQ(events, 2 * kScans);
  EXPECT_EQ(reader.trailing_bytes(), 0);
}

// ---------------------------------------------------------------------------------------
// Item 1: the 92-byte scan whose count overflows LCM's size computation, in a log.

struct OverflowCase {
  std::string name;
  int32_t num_ranges, num_intensities;
};
void PrintTo(const OverflowCase& c, std::ostream* os) { *os << c.name; }

class OverflowingScanInALogTest : public HostileFilesTest, public ::testing::WithParamInterface<OverflowCase> {
 protected:
  // The survey with the hostile scan between stations 9 and 10; returns its byte offset.
  int64_t WriteLog(const std::string& path) {
    int64_t offset = -1;
    const OverflowCase& c = GetParam();
    Survey([&](RawLog& log, int k) {
      if (k == kScans / 2)
        offset = log.Add("LADAR_SCAN", kT0 + int64_t{k} * 1'000'000 - 500'000,
                         testing::ScanWithCounts(c.num_ranges, c.num_intensities, kT0 + int64_t{k} * 1'000'000 - 500'000,
                                                 1000));
    }).Save(path);
    return offset;
  }
};

TEST_P(OverflowingScanInALogTest, ContourMapperDoesNotCrashAndMapsTheValidScans) {
  const std::string log = dir_ / "hostile.lcm";
  WriteLog(log);
  const ProcessResult r = Mapper(log);
  ExpectNoCrashAndBounded(r, "contour_mapper --log with a " + GetParam().name + " scan");
  if (r.exit_code == 0) {
    EXPECT_FALSE(LinesWith(r.output, {"LADAR_SCAN"}).empty())
        << "the bad scan must be logged in one line naming its channel\n"
        << Tail(r.output);
    EXPECT_EQ(LoadPosesCsv(dir_ / "poses.csv").size(), static_cast<size_t>(kScans))
        << "every valid scan must still be mapped\n"
        << Tail(r.output);
  } else if (r.exit_code == 2) {
    EXPECT_FALSE(LinesWith(r.output, {log}).empty()) << "exit 2 must come with a line naming the file\n"
                                                     << Tail(r.output);
  }
}

TEST_P(OverflowingScanInALogTest, LogToolInfoReportsTheBadScan) {
  const std::string log = dir_ / "hostile.lcm";
  const int64_t offset = WriteLog(log);
  const ProcessResult r = Info(log);
  ExpectNoCrashAndBounded(r, "log_tool info with a " + GetParam().name + " scan");
  EXPECT_FALSE(LinesWith(r.output, {"LADAR_SCAN", std::to_string(offset)}).empty())
      << "the report must name the bad message: a line with its channel LADAR_SCAN and its byte offset " << offset
      << "\n"
      << Tail(r.output);
}

TEST_P(OverflowingScanInALogTest, LogToolRenderDoesNotCrash) {
  const std::string log = dir_ / "hostile.lcm";
  WriteLog(log);
  const ProcessResult r = Render(log);
  ExpectNoCrashAndBounded(r, "log_tool render with a " + GetParam().name + " scan");
  if (r.exit_code == 0) {
    EXPECT_TRUE(fs::exists(dir_ / "render.svg")) << Tail(r.output);
  } else if (r.exit_code == 2) {
    EXPECT_FALSE(LinesWith(r.output, {log}).empty()) << "exit 2 must come with a line naming the file\n"
                                                     << Tail(r.output);
  }
}

INSTANTIATE_TEST_SUITE_P(Item1, OverflowingScanInALogTest,
                         ::testing::Values(OverflowCase{"NumRanges2p29", testing::kCount2p29, 0},
                                           OverflowCase{"NumIntensities2p29", 0, testing::kCount2p29}),
                         [](const ::testing::TestParamInfo<OverflowCase>& p) { return p.param.name; });

// ---------------------------------------------------------------------------------------
// Item 10: log_tool info on negative and huge counts.

struct MalformedCase {
  std::string name;
  std::string channel;
  std::function<std::vector<uint8_t>()> payload;
};
void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.name; }

class MalformedCountInALogTest : public HostileFilesTest, public ::testing::WithParamInterface<MalformedCase> {};

TEST_P(MalformedCountInALogTest, LogToolInfoReportsTheMessageAsBad) {
  const MalformedCase& c = GetParam();
  const std::string log = dir_ / "hostile.lcm";
  int64_t offset = -1;
  Survey([&](RawLog& l, int k) {
    if (k == kScans / 2) offset = l.Add(c.channel, kT0 + int64_t{k} * 1'000'000 - 500'000, c.payload());
  }).Save(log);
  const ProcessResult r = Info(log);
  ExpectNoCrashAndBounded(r, "log_tool info with " + c.name + " on " + c.channel);
  EXPECT_FALSE(LinesWith(r.output, {c.channel, std::to_string(offset)}).empty())
      << "the report must name the bad message: a line with its channel " << c.channel << " and its byte offset "
      << offset << "\n"
      << Tail(r.output);
  // The rest of the log is still summarised.
  EXPECT_FALSE(LinesWith(r.output, {"ODOMETRY"}).empty()) << "no report of the other channels\n" << Tail(r.output);
}

INSTANTIATE_TEST_SUITE_P(
    Item10, MalformedCountInALogTest,
    ::testing::Values(
        MalformedCase{"ScanNumRangesMinus1", "LADAR_SCAN", [] { return testing::ScanWithCounts(-1, 0); }},
        MalformedCase{"ContourMapNumContoursMinus1", "CONTOUR_MAP",
                      [] { return testing::ContourMapWithContourCount(-1); }},
        MalformedCase{"ContourNumPointsMinus1", "CONTOUR_MAP", [] { return testing::ContourMapWithPointCount(-1); }},
        MalformedCase{"ContourMapNumContoursMax", "CONTOUR_MAP",
                      [] { return testing::ContourMapWithContourCount(testing::kCountMax); }},
        MalformedCase{"ContourMapNumContours2p24", "CONTOUR_MAP",
                      [] { return testing::ContourMapWithContourCount(testing::kCount2p24); }},
        MalformedCase{"ContourMapPayloadSizeMax", "CONTOUR_MAP",
                      [] { return testing::ContourMapWithPayloadSize(testing::kCountMax); }},
        MalformedCase{"LineMapNumSegments2p26", "LINE_MAP",
                      [] { return testing::LineMapWithSegmentCount(testing::kCount2p26); }}),
    [](const ::testing::TestParamInfo<MalformedCase>& p) { return p.param.name; });

// ---------------------------------------------------------------------------------------
// Item 8: an event header claiming 0x7fffffff bytes, after the survey.

TEST_F(HostileFilesTest, EventHeaderClaimingTwoGigabytesDoesNotCrashContourMapper) {
  const std::string log = dir_ / "hostile.lcm";
  RawLog raw = Survey();
  const int64_t offset =
      raw.AddHeader("LADAR_SCAN", kT0 + int64_t{kScans} * 1'000'000, 0x7fffffff, testing::PseudoRandomBytes(64, 8));
  raw.Save(log);
  const std::string out_log = dir_ / "out.lcm";
  const ProcessResult r = Mapper(log, {"--log-out", out_log});
  ExpectNoCrashAndBounded(r, "contour_mapper --log with an event header claiming 2^31-1 bytes");
  EXPECT_FALSE(LinesWith(r.output, {log}).empty())
      << "the damaged (or cut short) log must be named in a line on stderr\n"
      << Tail(r.output);
  if (r.exit_code == 2) {
    EXPECT_FALSE(LinesWith(r.output, {log, std::to_string(offset)}).empty())
        << "exit 2 must come with one line naming the file and the byte offset " << offset << " of the bad header\n"
        << Tail(r.output);
    EXPECT_FALSE(fs::exists(out_log)) << "a failed run must not leave an output log claiming to be complete";
  } else if (r.exit_code == 0) {
    EXPECT_TRUE(fs::exists(out_log)) << "a run that succeeded must close its output log\n" << Tail(r.output);
    EXPECT_FALSE(fs::exists(out_log + ".partial")) << "a run that succeeded must not leave its .partial";
  }
}

// ---------------------------------------------------------------------------------------
// Item 9: corrupt bytes over an event header in the middle of the log.

TEST_F(HostileFilesTest, CorruptBytesInTheMiddleAreAnErrorNamingFileAndOffset) {
  const std::string log = dir_ / "corrupt.lcm";
  RawLog raw = Survey();
  int64_t offset = -1;
  for (int64_t o : raw.event_offsets())
    if (o >= raw.size() / 5) {
      offset = o;
      break;
    }
  ASSERT_GT(offset, 0);
  const std::vector<uint8_t> garbage = testing::PseudoRandomBytes(64, 9);
  for (size_t i = 0; i + 4 <= garbage.size(); ++i)
    ASSERT_FALSE(garbage[i] == 0xED && garbage[i + 1] == 0xA1 && garbage[i + 2] == 0xDA && garbage[i + 3] == 0x01)
        << "the corrupt bytes must not hold an event magic number";
  raw.Overwrite(offset, garbage);
  raw.Save(log);
  const ProcessResult r = Mapper(log);
  Summarize(r, "contour_mapper --log with 64 corrupt bytes at byte " + std::to_string(offset));
  ASSERT_TRUE(r.exit_code.has_value()) << "contour_mapper still running after 60 s\n" << Tail(r.output);
  EXPECT_NE(*r.exit_code, 0) << "64 corrupt bytes at byte " << offset << " of " << raw.size()
                             << " (an event header at 20 % of the log) must be an error, not a silent success\n"
                             << Tail(r.output);
  EXPECT_LT(*r.exit_code, 128) << "contour_mapper crashed: " << DescribeExit(r.exit_code) << "\n" << Tail(r.output);
  EXPECT_FALSE(LinesWith(r.output, {log, std::to_string(offset)}).empty())
      << "the error must be one line naming the file " << log << " and the byte offset " << offset << "\n"
      << Tail(r.output);
  EXPECT_LT(r.peak_rss_kb, kMaxPeakRssKb) << "peak RSS " << r.peak_rss_kb / 1024 << " MB";
}

// ---------------------------------------------------------------------------------------
// The payload builders themselves: each count field sits where the generated encoder
// puts it (checked against encode() of a message whose arrays really hold the elements),
// and a RawLog is byte for byte what LogWriter writes. None decodes a hostile payload.

TEST(HostilePayloadsTest, CountFieldsAreWhereTheGeneratedEncoderPutsThem) {
  using testing::GetInt32BigEndian;
  {  // ladar_scan_t: one range, then one intensity
    std::vector<uint8_t> built = testing::ScanWithCounts(1, 0, 5, 6);
    EXPECT_EQ(built.size(), 92u);
    ladar_scan_t m{};
    ASSERT_EQ(m.decode(testing::ScanWithCounts(0, 0, 5, 6).data(), 0, 92), 92);
    m.num_ranges = 1;
    m.ranges = {2.5f};
    std::vector<uint8_t> full = EncodeMessage(m);
    full.erase(full.end() - 8, full.end() - 4);  // the range's 4 bytes
    EXPECT_EQ(full, built);
    m.num_ranges = 0;
    m.ranges.clear();
    m.num_intensities = 1;
    m.intensities = {7.0f};
    full = EncodeMessage(m);
    full.erase(full.end() - 4, full.end());
    EXPECT_EQ(full, testing::ScanWithCounts(0, 1, 5, 6));
    EXPECT_EQ(GetInt32BigEndian(testing::ScanWithCounts(testing::kCount2p29, 0), 92 - 8), testing::kCount2p29);
  }
  {  // contour_map_t with one contour of one point
    const std::vector<uint8_t> built = testing::ContourMapWithPointCount(1);
    EXPECT_EQ(built.size(), 54u);
    contour_map_t m{};
    ASSERT_EQ(m.decode(testing::ContourMapWithPointCount(0).data(), 0, 54), 54);
    m.contours[0].num_points = 1;
    m.contours[0].x = {1.0f};
    m.contours[0].y = {2.0f};
    std::vector<uint8_t> full = EncodeMessage(m);
    full.erase(full.begin() + testing::kContourNumPointsOffset + 4, full.begin() + testing::kContourNumPointsOffset + 12);
    EXPECT_EQ(full, built);
  }
  {  // contour_map_t: num_contours, payload_size
    contour_map_t m{};
    ASSERT_EQ(m.decode(testing::ContourMapWithContourCount(0).data(), 0, 41), 41);
    m.num_contours = 1;
    m.contours.resize(1);
    std::vector<uint8_t> full = EncodeMessage(m);
    full.erase(full.begin() + testing::kContourMapNumContoursOffset + 4,
               full.begin() + testing::kContourMapNumContoursOffset + 4 + 13);  // the empty contour
    EXPECT_EQ(full, testing::ContourMapWithContourCount(1));
    m.num_contours = 0;
    m.contours.clear();
    m.payload_size = 1;
    m.payload = {9};
    full = EncodeMessage(m);
    full.pop_back();
    EXPECT_EQ(full, testing::ContourMapWithPayloadSize(1));
  }
  {  // line_map_t with one segment
    const std::vector<uint8_t> built = testing::LineMapWithSegmentCount(1);
    EXPECT_EQ(built.size(), 34u);
    line_map_t m{};
    ASSERT_EQ(m.decode(testing::LineMapWithSegmentCount(0).data(), 0, 34), 34);
    m.num_segments = 1;
    m.segments.resize(1);
    std::vector<uint8_t> full = EncodeMessage(m);
    full.resize(full.size() - 32);
    EXPECT_EQ(full, built);
  }
  {  // the compressed map: a valid outer message whose payload inflates to the inner one
    const std::vector<uint8_t> inner = testing::ContourMapWithPointCount(testing::kCount2p29);
    const std::vector<uint8_t> packet = testing::CompressedContourMap(inner);
    EXPECT_LE(packet.size(), 80u) << "issue 11's packet is 75 bytes";
    contour_map_t outer{};
    ASSERT_EQ(outer.decode(packet.data(), 0, static_cast<int>(packet.size())), static_cast<int>(packet.size()));
    EXPECT_EQ(outer.encoding, contour_map_t::ENCODING_ZLIB);
    EXPECT_EQ(outer.uncompressed_size, static_cast<int32_t>(inner.size()));
  }
}

TEST(HostilePayloadsTest, RawLogIsWhatLogWriterWrites) {
  testing::TempDir dir("minenav_hostile_files");
  OdometryReading o;
  o.utime = kT0;
  o.pose = Pose2(1, 2, 0.5);
  const odometry_t m = ToLcm(o);
  const std::vector<uint8_t> bytes = {1, 2, 3};
  {
    LogWriter w(dir / "writer.lcm");
    w.Write("ODOMETRY", m);
    w.Write("RAW", 42, bytes.data(), 3);
    w.Close();
  }
  RawLog raw;
  EXPECT_EQ(raw.AddMessage("ODOMETRY", m), 0);
  EXPECT_EQ(raw.Add("RAW", 42, bytes), 28 + 8 + m.getEncodedSize());
  raw.Save(dir / "raw.lcm");
  EXPECT_EQ(ReadFile(dir / "raw.lcm"), ReadFile(dir / "writer.lcm"));
}

}  // namespace
}  // namespace minenav
