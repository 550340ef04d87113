#include "common/node/log_bus.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "common/file_io.h"
#include "minenav/odometry_t.hpp"
#include "minenav/vehicle_truth_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

namespace fs = std::filesystem;

TEST(LogBus, DispatchesInFileOrderToMatchingSubscribersAndRecordsPublications) {
  testing::TempDir dir("minenav_log_bus_test");
  const std::string in = dir / "in.lcm";
  {
    LogWriter w(in);
    for (int i = 0; i < 6; ++i) {
      odometry_t m{};
      m.utime = 100 * i;
      m.seq = i;
      w.Write(i % 2 ? "POSE_IPE" : "POSE_FPE", m);
    }
    w.Close();
  }
  ManualClock clock(42);
  LogBus bus(in, clock);
  std::vector<std::string> order;
  std::vector<int64_t> fpe_seqs;
  bus.Subscribe("POSE_.*", [&](const RawMessage& m) { order.emplace_back(m.channel); });
  Subscribe<odometry_t>(bus, "POSE_FPE", [&](const odometry_t& m) { fpe_seqs.push_back(m.seq); });
  std::vector<std::pair<std::string, int64_t>> published;
  bus.SetPublishCallback([&](const std::string& channel, int64_t utime, const uint8_t*, int size) {
    EXPECT_GT(size, 0);
    published.emplace_back(channel, utime);
  });
  bus.SetOutputLog(dir / "out.lcm");

  ASSERT_EQ(bus.PeekTimestamp(), 0);
  ASSERT_EQ(bus.PeekTimestamp(), 0);  // peeking twice does not consume
  while (bus.HandleFor(0) == 1) {
    vehicle_truth_t t{};
    Publish(bus, "OUT", t);
  }
  EXPECT_FALSE(bus.PeekTimestamp().has_value());
  EXPECT_EQ(order, (std::vector<std::string>{"POSE_FPE", "POSE_IPE", "POSE_FPE", "POSE_IPE", "POSE_FPE", "POSE_IPE"}));
  EXPECT_EQ(fpe_seqs, (std::vector<int64_t>{0, 2, 4}));
  EXPECT_EQ(bus.events_dispatched(), 6);
  ASSERT_EQ(published.size(), 6u);
  EXPECT_EQ(published[0], (std::pair<std::string, int64_t>{"OUT", 42}));  // stamped with the clock
  EXPECT_FALSE(fs::exists(dir / "out.lcm"));  // until Close()
  bus.Close();
  LogReader out(dir / "out.lcm");
  int n = 0;
  while (auto e = out.Next()) {
    EXPECT_EQ(e->channel, "OUT");
    EXPECT_EQ(e->timestamp, 42);
    ++n;
  }
  EXPECT_EQ(n, 6);
}

TEST(LogBus, HandlerExceptionsAreBadMessagesAndTheRunGoesOn) {
  testing::TempDir dir("minenav_log_bus_test");
  const std::string in = dir / "in.lcm";
  {
    LogWriter w(in);
    const uint8_t bytes[4] = {1, 2, 3, 4};
    for (int i = 0; i < 3; ++i) w.Write("RAW", i, bytes, 4);
    w.Close();
  }
  ManualClock clock;
  LogBus bus(in, clock);
  int calls = 0;
  bus.Subscribe("RAW", [&](const RawMessage&) {
    if (++calls == 2) throw std::runtime_error("boom");
  });
  while (bus.HandleFor(0)) {
  }
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(bus.counters().messages_bad, 1);
  EXPECT_EQ(bus.bad_by_channel().at("RAW"), 1);
}

TEST(LogBus, MissingLogIsAnInputError) {
  ManualClock clock;
  EXPECT_THROW(LogBus("/nonexistent/in.lcm", clock), InputError);
}

}  // namespace
}  // namespace minenav
