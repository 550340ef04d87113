#include "dataset_readers/carmen_log.h"

#include <bzlib.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <string>
#include <vector>

#include "common/angle.h"
#include "common/file_io.h"

namespace minenav {
namespace {

// Two FLASER lines of 4 readings, one ODOM, a comment, a PARAM and an ignored NEFF line.
constexpr const char* kSmall =
    "# CARMEN Logfile\n"
    "PARAM robot_front_laser_max 50.0 nohost 0\n"
    "ODOM 1.0 2.0 0.5 0.3 0.1 0.0 100.25 host 0.1\n"
    "FLASER 4 1.0 2.5 81.91 0.0 1.04 2.0 0.5 1.0 2.0 0.5 100.5 host 0.2\n"
    "NEFF 12.0 100.6 host 0.3\n"
    "\n"
    "FLASER 4 3 3 3 3 1.1 2.0 0.5 1.1 2.0 0.5 100.400001 host 0.4\n";

TEST(CarmenLogTest, ParsesFlaserOdomAndParam) {
  const CarmenLog log = ParseCarmenLog(kSmall, "small.clf");
  ASSERT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.scan_odometry.size(), 2u);
  ASSERT_EQ(log.odometry.size(), 1u);
  EXPECT_EQ(log.stats.lines, 7);
  EXPECT_EQ(log.stats.flaser_lines, 2);
  EXPECT_EQ(log.stats.odom_lines, 1);
  EXPECT_EQ(log.stats.param_lines, 1);
  EXPECT_EQ(log.stats.ignored_lines, 1);
  // 81.91 is beyond the PARAM maximum (50 m) and 0.0 is no return.
  EXPECT_EQ(log.stats.no_return_readings, 2);
  EXPECT_EQ(log.stats.scan_time_reversals, 1);

  const LadarScan& s = log.scans[0];
  EXPECT_EQ(s.utime, 100500000);
  EXPECT_EQ(s.scan_id, 0);
  EXPECT_EQ(s.sensor_id, "FLASER");
  EXPECT_DOUBLE_EQ(s.start_angle, -kPi / 2.0);
  EXPECT_DOUBLE_EQ(s.angle_step, kPi / 3.0);  // n = 4: pi / (n - 1)
  EXPECT_DOUBLE_EQ(s.max_range, 50.0);
  ASSERT_EQ(s.ranges.size(), 4u);
  EXPECT_FLOAT_EQ(s.ranges[0], 1.0f);
  EXPECT_FLOAT_EQ(s.ranges[1], 2.5f);
  EXPECT_TRUE(std::isnan(s.ranges[2]));
  EXPECT_TRUE(std::isnan(s.ranges[3]));
  EXPECT_TRUE(s.IsValid(0));
  EXPECT_FALSE(s.IsValid(2));
  // The laser sits 0.04 m ahead along heading 0.5 rad: robot^-1 * laser = (0.04 * cos... ).
  // laser - robot = (0.04, 0) in the world; in the robot frame (heading 0.5):
  EXPECT_NEAR(s.sensor_offset.x, 0.04 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(s.sensor_offset.y, -0.04 * std::sin(0.5), 1e-12);
  EXPECT_NEAR(s.sensor_offset.theta, 0.0, 1e-12);
  EXPECT_EQ(log.scan_odometry[0].utime, 100500000);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].pose.x, 1.0);
  EXPECT_EQ(log.scans[1].utime, 100400001);
  EXPECT_EQ(log.scans[1].scan_id, 1);

  const OdometryReading& o = log.odometry[0];
  EXPECT_EQ(o.utime, 100250000);
  EXPECT_DOUBLE_EQ(o.pose.x, 1.0);
  EXPECT_DOUBLE_EQ(o.pose.y, 2.0);
  EXPECT_DOUBLE_EQ(o.pose.theta, 0.5);
  EXPECT_DOUBLE_EQ(o.v, 0.3);
  EXPECT_DOUBLE_EQ(o.omega, 0.1);
}

TEST(CarmenLogTest, MonotonicTimesOption) {
  CarmenReadOptions options;
  options.monotonic_times = true;
  const CarmenLog log = ParseCarmenLog(kSmall, "small.clf", options);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.scans[0].utime, 100500000);
  EXPECT_EQ(log.scans[1].utime, 100500001);
  EXPECT_EQ(log.scan_odometry[1].utime, 100500001);
  EXPECT_EQ(log.stats.scan_time_reversals, 1);  // counted on the raw times

  std::vector<int64_t> t = {5, 3, 3, 10, 9};
  EXPECT_EQ(MakeStrictlyIncreasing(&t), 3);
  EXPECT_EQ(t, (std::vector<int64_t>{5, 6, 7, 10, 11}));
}

TEST(CarmenLogTest, FlaserAnglesFollowCarmen) {
  std::string line = "FLASER 180";
  for (int i = 0; i < 180; ++i) line += " 1.0";
  line += " 0 0 0 0 0 0 1.0 h 0\n";
  std::string line361 = "FLASER 361";
  for (int i = 0; i < 361; ++i) line361 += " 1.0";
  line361 += " 0 0 0 0 0 0 2.0 h 0\n";
  const CarmenLog log = ParseCarmenLog(line + line361, "angles.clf");
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_DOUBLE_EQ(log.scans[0].angle_step, DegToRad(1.0));
  EXPECT_NEAR(log.scans[0].Bearing(179), DegToRad(89.0), 1e-12);
  EXPECT_DOUBLE_EQ(log.scans[1].angle_step, DegToRad(0.5));
  EXPECT_NEAR(log.scans[1].Bearing(360), DegToRad(90.0), 1e-12);
  // Without a PARAM the cap applies: 80 m.
  EXPECT_DOUBLE_EQ(log.scans[0].max_range, 80.0);
}

TEST(CarmenLogTest, ParsesRobotLaser1) {
  // 3 readings, 0 remissions, laser 0.22 m ahead of a robot at (1, 1, pi/2), tv 0.5, rv 0.1.
  const std::string text =
      "ROBOTLASER1 0 -1.0 2.0 1.0 81.9 0.01 0 3 2.0 81.83 4.0 0 1.0 1.22 1.5707963267948966 "
      "1.0 1.0 1.5707963267948966 0.5 0.1 0 0 0 1232658478.161285 zoidberg2 -0.05\n";
  const CarmenLog log = ParseCarmenLog(text, "rl.clf");
  ASSERT_EQ(log.scans.size(), 1u);
  const LadarScan& s = log.scans[0];
  EXPECT_EQ(s.sensor_id, "ROBOTLASER1");
  EXPECT_EQ(s.utime, 1232658478161285);
  EXPECT_DOUBLE_EQ(s.start_angle, -1.0);
  EXPECT_DOUBLE_EQ(s.angle_step, 1.0);
  EXPECT_DOUBLE_EQ(s.max_range, 80.0);  // line says 81.9, capped
  EXPECT_TRUE(std::isnan(s.ranges[1]));  // 81.83: SICK no-return code
  EXPECT_FLOAT_EQ(s.ranges[2], 4.0f);
  EXPECT_NEAR(s.sensor_offset.x, 0.22, 1e-12);
  EXPECT_NEAR(s.sensor_offset.y, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].v, 0.5);
  EXPECT_DOUBLE_EQ(log.scan_odometry[0].omega, 0.1);
  EXPECT_EQ(log.stats.robotlaser1_lines, 1);
}

void ExpectError(const std::string& text, const std::string& fragment) {
  try {
    ParseCarmenLog(text, "bad.clf");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(CarmenLogTest, MalformedLinesNameFileAndLine) {
  ExpectError("# c\nFLASER 3 1 2 0 0 0 0 0 0 1.0 h 0\n", "bad.clf:2: FLASER: expected 14 fields");
  ExpectError("FLASER 2 1 x 0 0 0 0 0 0 1.0 h 0\n", "bad.clf:1: FLASER: range 'x' (field 4) is not a finite number");
  ExpectError("FLASER -2 0 0 0 0 0 0 1.0 h 0\n", "number of readings '-2'");
  ExpectError("ODOM 1 2 3 4 5 6 1x5 h 0\n", "bad.clf:1: ODOM: ipc timestamp '1x5'");
  ExpectError("ODOM 1 2 3 4 5 1.0 h 0\n", "expected 10 fields");
  ExpectError("ODOM 1 2 nan 4 5 6 1.0 h 0\n", "theta 'nan'");
  ExpectError("PARAM robot_front_laser_max -3 h 0\n", "robot_front_laser_max -3 m is not positive");
  ExpectError("ROBOTLASER1 0 -1 2 0 81.9 0.01 0 1 2.0 0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 0\n",
              "angular resolution");
  ExpectError("ROBOTLASER1 0 -1 2 1 81.9 0.01 0 1 2.0 0 0 0 0 0 0 0 0 0 0 0 1.0 h 0\n", "expected 25 fields");
}

TEST(CarmenLogTest, TimestampsAreExact) {
  int64_t t = 0;
  ASSERT_TRUE(ParseCarmenTimestamp("976052857.337530", &t));
  EXPECT_EQ(t, 976052857337530);
  ASSERT_TRUE(ParseCarmenTimestamp("32.9068", &t));
  EXPECT_EQ(t, 32906800);
  ASSERT_TRUE(ParseCarmenTimestamp("7", &t));
  EXPECT_EQ(t, 7000000);
  ASSERT_TRUE(ParseCarmenTimestamp("1.08499e-42", &t));
  EXPECT_EQ(t, 0);
  ASSERT_TRUE(ParseCarmenTimestamp("1.5e2", &t));
  EXPECT_EQ(t, 150000000);
  ASSERT_TRUE(ParseCarmenTimestamp("1.1234567", &t));  // 7 decimals: rounded
  EXPECT_EQ(t, 1123457);
  EXPECT_FALSE(ParseCarmenTimestamp("inf", &t));
  EXPECT_FALSE(ParseCarmenTimestamp("abc", &t));
  EXPECT_FALSE(ParseCarmenTimestamp("", &t));
}

TEST(CarmenLogTest, ReadsGzipAndPlainFiles) {
  const std::string dir = ::testing::TempDir();
  const std::string plain = dir + "/carmen_small_" + std::to_string(::getpid()) + ".clf";
  const std::string gz = plain + ".gz";
  {
    std::ofstream out(plain);
    out << kSmall;
  }
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, kSmall, static_cast<unsigned>(std::string(kSmall).size()));
  gzclose(f);
  const CarmenLog a = ReadCarmenLog(plain);
  const CarmenLog b = ReadCarmenLog(gz);
  EXPECT_EQ(a.scans.size(), 2u);
  EXPECT_EQ(b.scans.size(), 2u);
  EXPECT_EQ(b.odometry.size(), 1u);
  std::filesystem::remove(plain);
  std::filesystem::remove(gz);
  EXPECT_THROW(ReadCarmenLog(dir + "/no_such_file.clf"), InputError);
}

// ---- Hostile input (issue 11): truncated archives, endless lines, huge fields.

std::string TempFile(const std::string& name) {
  return ::testing::TempDir() + "/carmen_" + std::to_string(::getpid()) + "_" + name;
}

// `count` FLASER lines of 4 readings, scan k at 100 + k s.
std::string FlaserLines(int first, int count) {
  std::string text;
  for (int k = first; k < first + count; ++k)
    text += "FLASER 4 1 2 3 4 0 0 0 0 0 0 " + std::to_string(100 + k) + ".5 host 0\n";
  return text;
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Expects ReadCarmenLog(path) to throw one line containing the path and every fragment.
void ExpectReadError(const std::string& path, const std::vector<std::string>& fragments) {
  try {
    const CarmenLog log = ReadCarmenLog(path);
    ADD_FAILURE() << path << ": no error, " << log.scans.size() << " scans";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path, 0), 0u) << what;
    for (const std::string& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_LT(what.size(), 400u) << what;
  }
}

TEST(CarmenLogHostileTest, AGzipCutShortIsAnErrorNotAShorterLog) {
  const std::string gz = TempFile("cut.clf.gz");
  // 50 scans; after 11 a sync flush, so a file cut there decodes cleanly up to scan 11 (the
  // probe's case: exit 0 with 11 of 50 scans).
  gzFile f = gzopen(gz.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  const std::string head = FlaserLines(0, 11), tail = FlaserLines(11, 39);
  ASSERT_EQ(gzwrite(f, head.data(), static_cast<unsigned>(head.size())), static_cast<int>(head.size()));
  ASSERT_EQ(gzflush(f, Z_SYNC_FLUSH), Z_OK);
  const auto flush_point = static_cast<size_t>(std::filesystem::file_size(gz));
  ASSERT_EQ(gzwrite(f, tail.data(), static_cast<unsigned>(tail.size())), static_cast<int>(tail.size()));
  ASSERT_EQ(gzclose(f), Z_OK);
  EXPECT_EQ(ReadCarmenLog(gz).scans.size(), 50u);  // the whole file is fine

  const std::string whole = ReadBytes(gz);
  ASSERT_GT(whole.size(), flush_point + 8);
  const std::string cut = TempFile("cut_at.clf.gz");
  for (const size_t size : {flush_point, whole.size() / 2 + flush_point / 2, whole.size() - 4, whole.size() - 1}) {
    WriteBytes(cut, whole.substr(0, size));
    SCOPED_TRACE("cut at " + std::to_string(size) + " of " + std::to_string(whole.size()) + " bytes");
    ExpectReadError(cut, {"truncated", "gzip"});
  }
  std::filesystem::remove(gz);
  std::filesystem::remove(cut);
}

TEST(CarmenLogHostileTest, ABzip2CutShortIsAnError) {
  // Two concatenated streams (as pbzip2 writes), 20 + 30 scans.
  auto compress = [](const std::string& text) {
    std::string out(text.size() + text.size() / 100 + 600, '\0');
    auto size = static_cast<unsigned>(out.size());
    EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &size, const_cast<char*>(text.data()),
                                       static_cast<unsigned>(text.size()), 9, 0, 0),
              BZ_OK);
    out.resize(size);
    return out;
  };
  const std::string first = compress(FlaserLines(0, 20)), second = compress(FlaserLines(20, 30));
  const std::string bz = TempFile("cut.clf.bz2");
  WriteBytes(bz, first + second);
  EXPECT_EQ(ReadCarmenLog(bz).scans.size(), 50u);
  const std::string whole = first + second;
  for (const size_t size : {first.size() / 2, first.size() + second.size() / 2, whole.size() - 1}) {
    WriteBytes(bz, whole.substr(0, size));
    SCOPED_TRACE("cut at " + std::to_string(size) + " of " + std::to_string(whole.size()) + " bytes");
    ExpectReadError(bz, {"truncated", "bzip2"});
  }
  std::filesystem::remove(bz);
}

TEST(CarmenLogHostileTest, AnEndlessLineIsRefusedBeforeItFillsMemory) {
  // A gzip bomb: 512 concatenated gzip members of 1 MiB of 'x' each (about 1 KB each on
  // disk) decompress to one line of 512 MiB. The reader must refuse the line once it
  // passes 1 MiB instead of decompressing it all (the probe's 3 MB bomb read 3 GB).
  constexpr size_t kMiB = size_t{1} << 20;
  const std::string member_path = TempFile("member.gz");
  {
    gzFile f = gzopen(member_path.c_str(), "wb9");
    ASSERT_NE(f, nullptr);
    const std::string x(kMiB, 'x');
    ASSERT_EQ(gzwrite(f, x.data(), static_cast<unsigned>(x.size())), static_cast<int>(x.size()));
    ASSERT_EQ(gzclose(f), Z_OK);
  }
  const std::string member = ReadBytes(member_path);
  std::filesystem::remove(member_path);
  const std::string bomb = TempFile("bomb.clf.gz");
  {  // A first member "FLASER " makes it look like a log; gzip members concatenate.
    const std::string prefix_path = TempFile("prefix.gz");
    gzFile f = gzopen(prefix_path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(gzwrite(f, "FLASER ", 7), 7);
    ASSERT_EQ(gzclose(f), Z_OK);
    std::ofstream out(bomb, std::ios::binary);
    out << ReadBytes(prefix_path);
    for (int i = 0; i < 512; ++i) out << member;
    std::filesystem::remove(prefix_path);
  }
  ASSERT_LT(std::filesystem::file_size(bomb), 2 * kMiB);

  // In a child process with its address space capped at 256 MiB (not under AddressSanitizer,
  // whose shadow memory needs terabytes of address space), so the old read-it-all code
  // fails with bad_alloc instead of taking 512 MiB of this shared machine; the parent
  // checks the child's peak resident memory either way.
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::close(pipe_fds[0]);
#ifndef __SANITIZE_ADDRESS__
    const rlimit cap{256 * kMiB, 256 * kMiB};
    ::setrlimit(RLIMIT_AS, &cap);
#endif
    int code = 0;
    std::string message;
    try {
      const CarmenLog log = ReadCarmenLog(bomb);
      message = "no error: " + std::to_string(log.stats.lines) + " lines";
      code = 10;
    } catch (const InputError& e) {
      message = e.what();
    } catch (const std::bad_alloc&) {
      message = "out of memory (bad_alloc): the reader holds the whole line";
      code = 11;
    } catch (const std::exception& e) {
      message = std::string("other exception: ") + e.what();
      code = 12;
    }
    message.resize(std::min<size_t>(message.size(), 4000));  // fits the pipe: never blocks
    if (::write(pipe_fds[1], message.data(), message.size()) < 0) code = 13;
    ::_exit(code);
  }
  ::close(pipe_fds[1]);
  int status = 0;
  rusage usage{};
  ASSERT_EQ(::wait4(pid, &status, 0, &usage), pid);
  std::string message(4096, '\0');
  const ssize_t got = ::read(pipe_fds[0], message.data(), message.size());
  ::close(pipe_fds[0]);
  message.resize(got > 0 ? static_cast<size_t>(got) : 0);
  std::filesystem::remove(bomb);
  ASSERT_TRUE(WIFEXITED(status)) << "child killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0) << message;
  EXPECT_NE(message.find(bomb + ":1: line longer than 1048576 bytes"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  // ru_maxrss is in KiB. What the test process already had plus a line of 1 MiB and a
  // chunk (measured: 6 MiB), far from the 512 MiB of the whole line (the old code: 138 MiB
  // when bad_alloc stopped it at the 256 MiB cap).
  EXPECT_LT(usage.ru_maxrss, 64 * 1024) << "peak resident memory " << usage.ru_maxrss << " KiB";
}

TEST(CarmenLogHostileTest, TheLineLimitAppliesToTextInMemoryAndIsAnOption) {
  const std::string long_line = "FLASER " + std::string(2 << 20, '1') + "\n";
  ExpectError(FlaserLines(0, 2) + long_line, "bad.clf:3: line longer than 1048576 bytes");
  CarmenReadOptions small;
  small.max_line_bytes = 40;
  EXPECT_THROW(ParseCarmenLog(FlaserLines(0, 1), "x.clf", small), InputError);  // 42 bytes
  EXPECT_EQ(ParseCarmenLog(FlaserLines(0, 1), "x.clf").scans.size(), 1u);
}

TEST(CarmenLogHostileTest, ErrorsQuoteAtMost80BytesOfTheInput) {
  // A 200 KB field (within the line limit): the message shows 80 bytes of it and "...".
  const std::string huge(200000, 'y');
  const std::string line = "FLASER 2 " + huge + " 1 0 0 0 0 0 0 1.0 h 0\n";
  try {
    ParseCarmenLog(line, "big.clf");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), 200u) << what.substr(0, 300);
    EXPECT_NE(what.find("big.clf:1: FLASER: range '" + std::string(80, 'y') + "...' (field 3) is not a finite number"),
              std::string::npos)
        << what.substr(0, 300);
  }
  // Bytes that would break the line or drive a terminal are shown as \xHH.
  ExpectError("ODOM 1 2 3 4 5 6 1\x1b[2J\v5 h 0\n", "ipc timestamp '1\\x1b[2J\\x0b5' (field 8)");
  ExpectError("PARAM robot_front_laser_max -" + std::string(100, '9') + " h 0\n",
              "robot_front_laser_max -" + std::string(79, '9') + "... m is not positive");
}

}  // namespace
}  // namespace minenav
