#include "common/node/event_log.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "common/file_io.h"
#include "minenav/odometry_t.hpp"

namespace minenav {
namespace {

namespace fs = std::filesystem;

// A directory of this process's files, removed when the test binary exits.
struct TempDir {
  fs::path path = fs::temp_directory_path() / ("minenav_event_log_test_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string TempPath(const std::string& name) {
  static TempDir dir;
  return (dir.path / name).string();
}

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

TEST(EventLog, GarbageFileHasNoEvents) {
  const std::string path = TempPath("garbage.lcm");
  {
    std::ofstream out(path, std::ios::binary);
    for (int i = 0; i < 1000; ++i) out.put(static_cast<char>(i * 7));
  }
  LogReader reader(path);
  EXPECT_FALSE(reader.Next().has_value());
  EXPECT_EQ(reader.trailing_bytes(), 1000);
}

}  // namespace
}  // namespace minenav
