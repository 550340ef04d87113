// command_attacker: what someone on the vehicle network without the key can do to the signed
// command channels (issue 16, "Security"; common/node/auth_bus.h). It listens to its channels
// for --capture seconds, keeping every message it hears (signed ones included), then for
// --attack seconds publishes on each channel, in turn:
//   - replayed: the captured messages as they were, bytes unchanged (valid tags, old seq);
//   - forged:   a message signed with a key of its own under the key id of the captured
//               messages (so the receiver does look at the tag): a captured payload of the
//               channel's own type re-signed, or a full-speed drive command when nothing was
//               captured there (the tag is checked before decoding: the type cannot help);
//   - tampered: a captured drive command with its speed changed, trailer kept;
//   - unsigned: the forged payload with no trailer.
// --rate: rounds per second (one message of each kind per channel a round); 0 = as fast as
// it can. It prints one line per channel with what it sent there and a line of totals.
// Used by tests/bus/command_auth_bus_test.cc (a flood beside vehicle_sim) and, during the
// whole mission, by tests/bus/mission_test.sh (scripts/run_demo.sh --attack). Not part of
// the fleet.
//
//   command_attacker [--channel C[,C...]] [--capture S] [--attack S] [--rate HZ]   (LCM_DEFAULT_URL)
// --channel: by default every channel --auth.signed-channels signs by default.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "common/message_auth.h"
#include "common/node/auth_bus.h"
#include "common/node/bus.h"
#include "common/node/lcm_bus.h"
#include "minenav/drive_command_t.hpp"

namespace {

using SteadyClock = std::chrono::steady_clock;

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

// What was sent on one channel.
struct ChannelAttack {
  std::vector<std::vector<uint8_t>> captured;
  uint32_t key_id = 1;
  int signed_captured = 0;
  std::vector<uint8_t> forged_body;  // the payload forged and unsigned messages carry
  minenav::AuthKeyRing own_key;      // the attacker's key, under the captured key id
  size_t next_capture = 0;
  int64_t replayed = 0, forged = 0, tampered = 0, unsigned_sent = 0;
};

std::vector<std::string> SplitChannels(const std::string& list) {
  std::vector<std::string> out;
  size_t begin = 0;
  while (begin <= list.size()) {
    const size_t comma = std::min(list.find(',', begin), list.size());
    if (comma > begin) out.push_back(list.substr(begin, comma - begin));
    begin = comma + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace minenav;
  std::string channels_flag = AuthOptions{}.signed_channels;  // every channel the fleet signs
  double capture_s = 2.0, attack_s = 3.0, rate_hz = 0.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--channel") == 0) {
      channels_flag = argv[i + 1];
    } else if (std::strcmp(argv[i], "--capture") == 0) {
      capture_s = std::atof(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--attack") == 0) {
      attack_s = std::atof(argv[i + 1]);
    } else if (std::strcmp(argv[i], "--rate") == 0) {
      rate_hz = std::atof(argv[i + 1]);
    } else {
      std::fprintf(stderr, "usage: command_attacker [--channel C[,C...]] [--capture S] [--attack S] [--rate HZ]\n");
      return 2;
    }
  }
  const std::vector<std::string> channels = SplitChannels(channels_flag);
  if (channels.empty() || !(capture_s >= 0) || !(attack_s >= 0) || !(rate_hz >= 0)) {
    std::fprintf(stderr, "command_attacker: --channel names a channel; --capture, --attack and --rate are >= 0\n");
    return 2;
  }
  try {
    LcmBus bus(ResolveLcmUrl(""), 10000);
    std::map<std::string, ChannelAttack> attacks;
    for (const std::string& channel : channels) {
      ChannelAttack& a = attacks[channel];
      bus.Subscribe(channel, [&a](const RawMessage& raw) {
        if (a.captured.size() < 100000) a.captured.emplace_back(raw.data, raw.data + raw.size);
      });
    }
    const auto capture_end = SteadyClock::now() + std::chrono::duration<double>(capture_s);
    while (SteadyClock::now() < capture_end) bus.HandleFor(10'000);
    for (auto& [channel, a] : attacks) {
      for (const std::vector<uint8_t>& m : a.captured) {
        AuthTrailer t;
        if (!ParseAuthTrailer(m.data(), static_cast<int>(m.size()), &t)) continue;
        ++a.signed_captured;
        a.key_id = t.key_id;
        a.forged_body.assign(m.begin(), m.begin() + StripAuthTrailer(m.data(), static_cast<int>(m.size())));
      }
      if (a.forged_body.empty()) a.forged_body = EncodeMessage(FullSpeed(1));
      a.own_key = AuthKeyRing{{RandomAuthKey(a.key_id)}};
      std::fprintf(stderr, "command_attacker: captured %zu message(s) on %s (%d signed)\n", a.captured.size(),
                   channel.c_str(), a.signed_captured);
    }
    std::fprintf(stderr, "command_attacker: attacking %zu channel(s) for %.1f s\n", attacks.size(), attack_s);
    MessageSigner forger(RandomSenderId());
    const auto attack_end =
        SteadyClock::now() + std::chrono::duration_cast<SteadyClock::duration>(std::chrono::duration<double>(attack_s));
    const auto round_period = std::chrono::duration<double>(rate_hz > 0 ? 1.0 / rate_hz : 0.0);
    auto next_round = SteadyClock::now();
    while (SteadyClock::now() < attack_end) {
      for (auto& [channel, a] : attacks) {
        if (!a.captured.empty()) {
          const std::vector<uint8_t>& m = a.captured[a.next_capture++ % a.captured.size()];
          bus.Publish(channel, m.data(), static_cast<int>(m.size()));
          ++a.replayed;
          const int payload = StripAuthTrailer(m.data(), static_cast<int>(m.size()));
          if (payload != static_cast<int>(m.size()) && payload > 8) {
            // A drive command goes full speed; any other message has its last payload byte changed.
            std::vector<uint8_t> changed(m.begin(), m.begin() + payload);
            drive_command_t d{};
            if (d.decode(m.data(), 0, payload) > 0) {
              d.v = 1.0;
              d.mode = drive_command_t::VELOCITY;
              changed = EncodeMessage(d);
            } else {
              changed.back() ^= 0x5a;
            }
            changed.insert(changed.end(), m.begin() + payload, m.end());
            bus.Publish(channel, changed.data(), static_cast<int>(changed.size()));
            ++a.tampered;
          }
        }
        const std::vector<uint8_t> forgery = forger.Sign(a.own_key, channel, a.forged_body.data(),
                                                         static_cast<int>(a.forged_body.size()), WallUtime());
        bus.Publish(channel, forgery.data(), static_cast<int>(forgery.size()));
        ++a.forged;
        bus.Publish(channel, a.forged_body.data(), static_cast<int>(a.forged_body.size()));
        ++a.unsigned_sent;
      }
      if (rate_hz > 0) {
        next_round += std::chrono::duration_cast<SteadyClock::duration>(round_period);
        std::this_thread::sleep_until(std::min(next_round, attack_end));
      }
    }
    int64_t replayed = 0, forged = 0, tampered = 0, unsigned_sent = 0;
    for (const auto& [channel, a] : attacks) {
      std::printf("%s replayed %lld forged %lld tampered %lld unsigned %lld\n", channel.c_str(),
                  static_cast<long long>(a.replayed), static_cast<long long>(a.forged),
                  static_cast<long long>(a.tampered), static_cast<long long>(a.unsigned_sent));
      replayed += a.replayed;
      forged += a.forged;
      tampered += a.tampered;
      unsigned_sent += a.unsigned_sent;
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
