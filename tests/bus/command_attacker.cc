// command_attacker: what someone on the vehicle network without the key can do to the signed
// command channels (issue 16, "Security"; common/node/auth_bus.h). It listens to a channel for
// --capture seconds, keeping every message it hears (signed ones included), then for --attack
// seconds publishes as fast as it can, in turn:
//   - replayed: the captured messages as they were, bytes unchanged (valid tags, old seq);
//   - forged:   a full-speed drive command signed with a key of its own under the key id of
//               the captured messages (so the receiver does look at the tag);
//   - tampered: a captured message with its speed changed, trailer kept;
//   - unsigned: a full-speed drive command with no trailer.
// It prints what it sent, one line. Used by tests/bus/command_auth_bus_test.cc and, during the
// mission, by tests/bus/mission_test.sh. Not part of the fleet.
//
//   command_attacker [--channel DRIVE_COMMAND] [--capture S] [--attack S]   (LCM_DEFAULT_URL)

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/message_auth.h"
#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"

namespace {

using Clock = std::chrono::steady_clock;

int64_t WallUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

minenav::drive_command_t FullSpeed(int64_t seq) {
  minenav::drive_command_t m{};
  m.utime = WallUtime();
  m.seq = seq;
  m.mode = minenav::drive_command_t::VELOCITY;
  m.v = 1.0;
  m.omega = 0.3;
  m.timeout = 1.0;
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace minenav;
  std::string channel = "DRIVE_COMMAND";
  double capture_s = 2.0, attack_s = 3.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--channel") == 0) {
      channel = argv[i + 1];
    } else if (std::strcmp(argv[i], "--capture") == 0) {
      capture_s = std::atof(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--attack") == 0) {
      attack_s = std::atof(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: command_attacker [--channel C] [--capture S] [--attack S]\n");
      return 2;
    }
  }
  try {
    LcmBus bus(ResolveLcmUrl(""), 10000);
    std::vector<std::vector<uint8_t>> captured;
    bus.Subscribe(channel, [&](const RawMessage& raw) {
      if (captured.size() < 100000) captured.emplace_back(raw.data, raw.data + raw.size);
    });
    const auto capture_end = Clock::now() + std::chrono::duration<double>(capture_s);
    while (Clock::now() < capture_end) bus.HandleFor(10'000);
    int signed_captured = 0;
    uint32_t key_id = 1;
    for (const std::vector<uint8_t>& m : captured) {
      AuthTrailer t;
      if (ParseAuthTrailer(m.data(), static_cast<int>(m.size()), &t)) {
        ++signed_captured;
        key_id = t.key_id;
      }
    }
    std::fprintf(stderr, "command_attacker: captured %zu message(s) on %s (%d signed); attacking for %.1f s\n",
                 captured.size(), channel.c_str(), signed_captured, attack_s);
    const AuthKeyRing own_key{{RandomAuthKey(key_id)}};
    MessageSigner forger(RandomSenderId());
    int64_t replayed = 0, forged = 0, tampered = 0, unsigned_sent = 0, seq = 1;
    const auto attack_end = Clock::now() + std::chrono::duration<double>(attack_s);
    size_t next_capture = 0;
    while (Clock::now() < attack_end) {
      if (!captured.empty()) {
        const std::vector<uint8_t>& m = captured[next_capture++ % captured.size()];
        bus.Publish(channel, m.data(), static_cast<int>(m.size()));
        ++replayed;
        const int payload = StripAuthTrailer(m.data(), static_cast<int>(m.size()));
        if (payload != static_cast<int>(m.size()) && payload >= 8 + 8 + 8 + 1 + 8) {
          drive_command_t d{};
          if (d.decode(m.data(), 0, payload) > 0) {
            d.v = 1.0;
            d.mode = drive_command_t::VELOCITY;
            std::vector<uint8_t> changed = EncodeMessage(d);
            changed.insert(changed.end(), m.begin() + payload, m.end());
            bus.Publish(channel, changed.data(), static_cast<int>(changed.size()));
            ++tampered;
          }
        }
      }
      const std::vector<uint8_t> body = EncodeMessage(FullSpeed(seq++));
      const std::vector<uint8_t> forgery =
          forger.Sign(own_key, channel, body.data(), static_cast<int>(body.size()), WallUtime());
      bus.Publish(channel, forgery.data(), static_cast<int>(forgery.size()));
      ++forged;
      bus.Publish(channel, body.data(), static_cast<int>(body.size()));
      ++unsigned_sent;
    }
    std::printf("replayed %lld forged %lld tampered %lld unsigned %lld\n", static_cast<long long>(replayed),
                static_cast<long long>(forged), static_cast<long long>(tampered),
                static_cast<long long>(unsigned_sent));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "command_attacker: %s\n", e.what());
    return 3;
  }
}
