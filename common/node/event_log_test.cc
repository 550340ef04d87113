#include "common/node/event_log.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/file_io.h"
#include "minenav/odometry_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;

using testing::TempPath;

odometry_t Odometry(int64_t utime, double x) {
  odometry_t m{};
  m.utime = utime;
  m.pose.x = x;
  return m;
}

TEST(EventLog, WriteThenReadBackInOrder) {
  const std::string path = TempPath("roundtrip.lcm");
  {
    LogWriter writer(path);
    for (int i = 0; i < 50; ++i) writer.Write("ODOMETRY", Odometry(1000 + 100 * i, 0.1 * i));
    const uint8_t raw[3] = {1, 2, 3};
    writer.Write("RAW", 999999, raw, 3);
    EXPECT_FALSE(fs::exists(path));  // only the .partial file until Close()
    writer.Close();
    EXPECT_EQ(writer.events_written(), 51);
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".partial"));
  LogReader reader(path);
  for (int i = 0; i < 50; ++i) {
    auto e = reader.Next();
    ASSERT_TRUE(e.has_value());
    EXPECT_EQ(e->channel, "ODOMETRY");
    EXPECT_EQ(e->timestamp, 1000 + 100 * i);
    odometry_t m{};
    std::string error;
    ASSERT_TRUE(DecodeMessage(e->data.data(), static_cast<int>(e->data.size()), e->channel, &m, &error));
    EXPECT_DOUBLE_EQ(m.pose.x, 0.1 * i);
  }
  auto raw = reader.Next();
  ASSERT_TRUE(raw.has_value());
  EXPECT_EQ(raw->timestamp, 999999);
  EXPECT_EQ(raw->data, (std::vector<uint8_t>{1, 2, 3}));
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_EQ(reader.events_read(), 51);
  EXPECT_EQ(reader.trailing_bytes(), 0);
}

TEST(EventLog, WriterWithoutCloseLeavesNothing) {
  const std::string path = TempPath("abandoned.lcm");
  {
    LogWriter writer(path);
    writer.Write("ODOMETRY", Odometry(1, 0));
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".partial"));
}

TEST(EventLog, TruncatedLogReadsCompleteEventsAndReportsTheRest) {
  const std::string path = TempPath("truncated.lcm");
  {
    LogWriter writer(path);
    for (int i = 0; i < 10; ++i) writer.Write("ODOMETRY", Odometry(i, i));
    writer.Close();
  }
  const auto full = fs::file_size(path);
  fs::resize_file(path, full - 20);  // cut the last event short
  LogReader reader(path);
  int n = 0;
  while (reader.Next()) ++n;
  EXPECT_EQ(n, 9);
  EXPECT_GT(reader.trailing_bytes(), 0);
  EXPECT_LT(reader.trailing_bytes(), static_cast<int64_t>(full / 10));
}

TEST(EventLog, BadPathsAreInputErrors) {
  EXPECT_THROW(LogReader("/nonexistent/dir/x.lcm"), InputError);
  EXPECT_THROW(LogReader(fs::temp_directory_path().string()), InputError);
  EXPECT_THROW(LogWriter("/nonexistent/dir/x.lcm"), InputError);
}

// Issue 11, items 8 and 9: LCM's own reader skipped garbage silently (a garbage file was
// "a log with no events"; 64 corrupt bytes at 20 % gave a map of 3 of 20 scans and exit 0)
// and crashed on a header claiming 2 GB. Damage is now an error naming the byte offset.
TEST(EventLog, GarbageIsAnErrorNamingTheByteOffset) {
  const std::string path = TempPath("garbage.lcm");
  {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 1000; ++i) out.put(static_cast<char>(i * 7));
  }
  LogReader reader(path);
  try {
    reader.Next();
    FAIL() << "garbage read as a log";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("event at byte 0: bad magic"), std::string::npos) << e.what();
  }
}

std::string WriteOdometryLog(const std::string& name, int events) {
  const std::string path = TempPath(name);
  LogWriter writer(path);
  for (int k = 0; k < events; ++k) {
    odometry_t m{};
    m.utime = 1'000'000 + k;
    writer.Write("ODOMETRY", m);
  }
  writer.Close();
  return path;
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(EventLog, CorruptionInTheMiddleIsAnErrorNotASilentSkip) {
  const std::string path = WriteOdometryLog("middle.lcm", 20);
  std::string bytes = ReadBytes(path);
  const size_t at = bytes.size() / 5;
  for (size_t i = 0; i < 64; ++i) bytes[at + i] = static_cast<char>(0x5A);
  WriteBytes(path, bytes);
  LogReader reader(path);
  int events = 0;
  EXPECT_THROW(
      {
        while (reader.Next()) ++events;
      },
      InputError);
  EXPECT_LE(events, 5);
}

TEST(EventLog, AHeaderClaimingTwoGigabytesIsAnError) {
  const std::string path = WriteOdometryLog("huge.lcm", 3);
  std::string bytes = ReadBytes(path);
  // The second event's data length (bytes 24..27 of its header).
  LogReader first(path);
  first.Next();
  const auto second = static_cast<size_t>(first.position());
  for (size_t i = 0; i < 4; ++i) bytes[second + 24 + i] = static_cast<char>(i == 0 ? 0x7f : 0xff);
  WriteBytes(path, bytes);
  LogReader reader(path);
  ASSERT_TRUE(reader.Next().has_value());
  try {
    reader.Next();
    FAIL() << "a 2 GB payload length was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("payload length 2147483647 is invalid"), std::string::npos) << e.what();
  }
}

TEST(EventLog, ALastEventCutShortEndsTheLogWithTrailingBytes) {
  const std::string path = WriteOdometryLog("cut.lcm", 5);
  const std::string bytes = ReadBytes(path);
  WriteBytes(path, bytes.substr(0, bytes.size() - 10));
  LogReader reader(path);
  int events = 0;
  while (reader.Next()) ++events;
  EXPECT_EQ(events, 4);
  EXPECT_GT(reader.trailing_bytes(), 0);
  EXPECT_NE(reader.truncation().find("truncated event"), std::string::npos) << reader.truncation();
}

TEST(EventLog, ALengthRunningPastTheEndWithEventsAfterItIsDamage) {
  const std::string path = WriteOdometryLog("overlong.lcm", 6);
  std::string bytes = ReadBytes(path);
  LogReader first(path);
  first.Next();
  const auto second = static_cast<size_t>(first.position());
  // Claims 100 MB: past the end, but the next events are still there.
  for (size_t i = 0; i < 4; ++i) bytes[second + 24 + i] = static_cast<char>(i == 0 ? 0x06 : 0x00);
  WriteBytes(path, bytes);
  LogReader reader(path);
  ASSERT_TRUE(reader.Next().has_value());
  EXPECT_THROW(reader.Next(), InputError);
}

}  // namespace
}  // namespace minenav
