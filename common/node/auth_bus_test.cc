#include "common/node/auth_bus.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "common/file_io.h"

#include "common/node/fake_bus.h"
#include "common/node/node_runtime.h"
#include "minenav/drive_command_t.hpp"
#include "minenav/heartbeat_t.hpp"
#include "minenav/odometry_t.hpp"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

constexpr int64_t kT0 = 1'700'000'000'000'000;

drive_command_t Drive(int64_t seq, double v) {
  drive_command_t m{};
  m.utime = kT0;
  m.seq = seq;
  m.mode = drive_command_t::VELOCITY;
  m.v = v;
  m.timeout = 0.5;
  return m;
}

// A publisher and a receiver, each an AuthBus over its own FakeBus, sharing a key file; what
// the publisher sends is carried to the receiver by hand (Carry), as the network would.
struct Pair {
  testing::TempDir dir{"auth_bus"};
  std::string key_file = dir / "fleet.key";
  ManualClock clock{kT0};
  FakeBus* sent = nullptr;
  FakeBus* received = nullptr;
  std::unique_ptr<AuthBus> publisher, receiver;
  std::vector<drive_command_t> drives;

  Pair() {
    SaveAuthKeyFile(key_file, AuthKeyRing{{RandomAuthKey(1)}});
    AuthOptions options;
    options.key_file = key_file;
    auto a = std::make_unique<FakeBus>();
    auto b = std::make_unique<FakeBus>();
    sent = a.get();
    received = b.get();
    publisher = std::make_unique<AuthBus>(std::move(a), options, clock);
    receiver = std::make_unique<AuthBus>(std::move(b), options, clock);
    Subscribe<drive_command_t>(*receiver, "DRIVE_COMMAND", [&](const drive_command_t& m) { drives.push_back(m); });
  }
  // Every publication so far, to the receiver, received at the clock's time.
  void Carry() {
    for (const FakeBus::Message& m : sent->published()) received->Inject(m.channel, m.data, clock.NowUtime());
    sent->ClearPublished();
    received->HandleFor(0);
  }
};

TEST(AuthBus, SignedCommandsArriveDecodedOthersPassUntouched) {
  Pair p;
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(1, 0.05));
  Publish(*p.publisher, "ODOMETRY", odometry_t{});
  ASSERT_EQ(p.sent->published().size(), 2u);
  EXPECT_EQ(p.sent->published()[0].data.size(), EncodeMessage(Drive(1, 0.05)).size() + kAuthTrailerBytes);
  EXPECT_EQ(p.sent->published()[1].data, EncodeMessage(odometry_t{}));  // unsigned channel: as before
  EXPECT_EQ(p.publisher->counters().published, 2);
  p.Carry();
  ASSERT_EQ(p.drives.size(), 1u);
  EXPECT_EQ(p.drives[0].v, 0.05);
  EXPECT_EQ(p.receiver->counters().messages_in, 1);
  EXPECT_EQ(p.receiver->counters().messages_bad, 0);
}

TEST(AuthBus, ForgedReplayedUnsignedAndTamperedCommandsNeverReachTheHandler) {
  Pair p;
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(1, 0.05));
  const std::vector<uint8_t> valid = p.sent->published()[0].data;
  p.Carry();
  ASSERT_EQ(p.drives.size(), 1u);
  // Replayed, unsigned, tampered, and forged with another key under the same id.
  p.received->Inject("DRIVE_COMMAND", valid, p.clock.NowUtime());
  p.received->InjectMessage("DRIVE_COMMAND", Drive(2, 1.0), p.clock.NowUtime());
  std::vector<uint8_t> tampered = valid;
  tampered[30] ^= 0x40;  // inside the payload's v
  p.received->Inject("DRIVE_COMMAND", tampered, p.clock.NowUtime());
  MessageSigner attacker(RandomSenderId());
  const std::vector<uint8_t> body = EncodeMessage(Drive(3, 1.0));
  p.received->Inject("DRIVE_COMMAND",
                     attacker.Sign(AuthKeyRing{{RandomAuthKey(1)}}, "DRIVE_COMMAND", body.data(),
                                   static_cast<int>(body.size()), p.clock.NowUtime()),
                     p.clock.NowUtime());
  // A valid command from the past (older than --auth.max-age when it arrives).
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(4, 1.0));
  p.clock.Advance(6'000'000);
  p.Carry();
  EXPECT_EQ(p.drives.size(), 1u);
  EXPECT_EQ(p.receiver->counters().messages_bad, 5);
  EXPECT_EQ(p.receiver->counters().auth_rejected, 5);
  EXPECT_EQ(p.receiver->bad_by_channel().at("DRIVE_COMMAND"), 5);
  EXPECT_EQ(p.receiver->auth_rejected_by_channel().at("DRIVE_COMMAND"), 5);
  EXPECT_NE(p.receiver->last_auth_rejection().find("too old"), std::string::npos) << p.receiver->last_auth_rejection();
  // The line the process logs when it stops names them per channel (mission_test.sh reads it).
  const std::string summary = ExitSummary(*p.receiver);
  EXPECT_NE(summary.find("1 message(s) handled, 5 bad"), std::string::npos) << summary;
  EXPECT_NE(summary.find("; refused by authentication: DRIVE_COMMAND 5"), std::string::npos) << summary;
  // A fresh one still passes.
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(5, 0.02));
  p.Carry();
  ASSERT_EQ(p.drives.size(), 2u);
  EXPECT_EQ(p.drives[1].seq, 5);
}

TEST(AuthBus, TwoSubscriptionsToASignedChannelBothGetEachMessageOnce) {
  Pair p;
  std::vector<int64_t> second;
  Subscribe<drive_command_t>(*p.receiver, "DRIVE_COMMAND", [&](const drive_command_t& m) { second.push_back(m.seq); });
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(1, 0.05));
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(2, 0.05));
  const std::vector<uint8_t> replay = p.sent->published()[0].data;
  p.Carry();
  p.received->Inject("DRIVE_COMMAND", replay, p.clock.NowUtime());
  p.received->HandleFor(0);
  ASSERT_EQ(p.drives.size(), 2u);
  EXPECT_EQ(second, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(p.receiver->counters().messages_in, 4);
  // The replay is refused once, for both subscriptions.
  EXPECT_EQ(p.receiver->counters().auth_rejected, 1);
}

TEST(AuthBus, ARotatedKeyFileIsPickedUpByPublisherAndReceiver) {
  Pair p;
  AuthKeyRing ring = LoadAuthKeyFile(p.key_file);
  ring.keys.push_back(RandomAuthKey(2));
  SaveAuthKeyFile(p.key_file, ring);
  p.clock.Advance(1'100'000);  // past the one-second look at the file
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(1, 0.05));
  AuthTrailer t;
  ASSERT_TRUE(ParseAuthTrailer(p.sent->published()[0].data.data(),
                               static_cast<int>(p.sent->published()[0].data.size()), &t));
  EXPECT_EQ(t.key_id, 2u);
  p.Carry();
  EXPECT_EQ(p.drives.size(), 1u);
  EXPECT_EQ(p.receiver->keys().keys.size(), 2u);
}

TEST(AuthBus, ReadersWithoutAKeyDecodeSignedMessages) {
  // lcm-logger records the trailer; a reader without authentication decodes the LCM message
  // before it, and StripAuthTrailer gives the message's bytes to whoever copies them.
  Pair p;
  Publish(*p.publisher, "DRIVE_COMMAND", Drive(7, 0.03));
  const std::vector<uint8_t> bytes = p.sent->published()[0].data;
  drive_command_t m{};
  std::string error;
  ASSERT_TRUE(DecodeMessage(bytes.data(), static_cast<int>(bytes.size()), "DRIVE_COMMAND", &m, &error)) << error;
  EXPECT_EQ(m.seq, 7);
  EXPECT_EQ(StripAuthTrailer(bytes.data(), static_cast<int>(bytes.size())),
            static_cast<int>(EncodeMessage(Drive(7, 0.03)).size()));
}

TEST(AuthBus, TheRuntimeWrapsItsBusAndItsHeartbeatSaysWhatWasRefused) {
  testing::TempDir dir("auth_bus");
  const std::string key_file = dir / "fleet.key";
  SaveAuthKeyFile(key_file, AuthKeyRing{{RandomAuthKey(1)}});
  auto owned = std::make_unique<FakeBus>();
  FakeBus& bus = *owned;
  ManualClock clock(kT0);
  NodeOptions options;
  options.auth.key_file = key_file;
  NodeRuntime runtime("auth_node", options);
  runtime.StartWith(std::move(owned), clock);
  int handled = 0;
  Subscribe<drive_command_t>(runtime.bus(), "DRIVE_COMMAND", [&](const drive_command_t&) { ++handled; });
  runtime.SpinOnce(0);
  bus.InjectMessage("DRIVE_COMMAND", Drive(1, 1.0), kT0);
  runtime.SpinOnce(0);  // handled (refused)
  clock.Advance(1'000'000);
  runtime.SpinOnce(0);  // the second heartbeat
  EXPECT_EQ(handled, 0);
  const std::vector<heartbeat_t> hb = bus.Decoded<heartbeat_t>("HEARTBEAT");
  ASSERT_EQ(hb.size(), 2u);
  EXPECT_EQ(hb[1].messages_bad, 1);
  EXPECT_EQ(hb[1].state, heartbeat_t::WARN);
  EXPECT_NE(hb[1].message.find("refused by authentication"), std::string::npos) << hb[1].message;
  EXPECT_NE(hb[1].message.find("unsigned"), std::string::npos) << hb[1].message;

  // A key file others can read stops the process at start-up (InputError: exit 2).
  ::chmod(key_file.c_str(), 0644);
  NodeRuntime refused("auth_node", options);
  EXPECT_THROW(refused.StartWith(std::make_unique<FakeBus>(), clock), InputError);
}

}  // namespace
}  // namespace minenav
