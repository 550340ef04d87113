#include "common/message_auth.h"

#include <gtest/gtest.h>

#include <set>

#include "common/file_io.h"

namespace minenav {
namespace {

constexpr int64_t kSecond = 1'000'000;
constexpr int64_t kNow = 1'700'000'000 * kSecond;

AuthKeyRing Ring(std::vector<AuthKey> keys) { return AuthKeyRing{std::move(keys)}; }

// A payload as LCM lays it out: an 8-byte fingerprint, then fields.
std::vector<uint8_t> Payload(int size = 40) {
  std::vector<uint8_t> p(static_cast<size_t>(size));
  for (int i = 0; i < size; ++i) p[i] = static_cast<uint8_t>(i * 37 + 11);
  return p;
}

struct Fixture {
  AuthKeyRing keys = Ring({RandomAuthKey(1)});
  MessageSigner signer{RandomSenderId()};
  MessageVerifier verifier{5 * kSecond};
  std::vector<uint8_t> Sign(const std::vector<uint8_t>& p, int64_t utime = kNow,
                            const std::string& channel = "DRIVE_COMMAND") {
    return signer.Sign(keys, channel, p.data(), static_cast<int>(p.size()), utime);
  }
  AuthResult Check(const std::vector<uint8_t>& m, int64_t now = kNow, const std::string& channel = "DRIVE_COMMAND") {
    return verifier.Verify(keys, channel, m.data(), static_cast<int>(m.size()), now).result;
  }
};

TEST(MessageAuth, SignedMessageVerifiesAndStripsToThePayload) {
  Fixture f;
  const std::vector<uint8_t> p = Payload();
  const std::vector<uint8_t> m = f.Sign(p);
  ASSERT_EQ(m.size(), p.size() + kAuthTrailerBytes);
  EXPECT_TRUE(std::equal(p.begin(), p.end(), m.begin()));  // the payload first, untouched
  const VerifyOutcome v = f.verifier.Verify(f.keys, "DRIVE_COMMAND", m.data(), static_cast<int>(m.size()), kNow);
  EXPECT_EQ(v.result, AuthResult::kAccepted);
  EXPECT_EQ(v.payload_size, static_cast<int>(p.size()));
  EXPECT_EQ(StripAuthTrailer(m.data(), static_cast<int>(m.size())), static_cast<int>(p.size()));
  EXPECT_EQ(StripAuthTrailer(p.data(), static_cast<int>(p.size())), static_cast<int>(p.size()));
}

TEST(MessageAuth, ATamperedByteAnywhereIsRefused) {
  Fixture f;
  const std::vector<uint8_t> m = f.Sign(Payload());
  // Every byte but the magic (whose change makes the message unsigned, refused too).
  for (size_t i = 0; i < m.size(); ++i) {
    for (uint8_t flip : {uint8_t{0x01}, uint8_t{0x80}}) {
      std::vector<uint8_t> bad = m;
      bad[i] ^= flip;
      const AuthResult r = f.Check(bad);
      EXPECT_NE(r, AuthResult::kAccepted) << "byte " << i << " flip " << int{flip};
      if (i < m.size() - kAuthTrailerBytes) {
        EXPECT_EQ(r, AuthResult::kBadTag) << "payload byte " << i;
      }
    }
  }
  // The untouched message still passes (no tampered copy consumed its sequence number).
  EXPECT_EQ(f.Check(m), AuthResult::kAccepted);
}

TEST(MessageAuth, AnotherChannelOrAnotherKeyIsRefused) {
  Fixture f;
  const std::vector<uint8_t> m = f.Sign(Payload());
  EXPECT_EQ(f.Check(m, kNow, "CUTTER_COMMAND"), AuthResult::kBadTag);
  // Forged: same key id, another key.
  Fixture attacker;
  attacker.keys = Ring({RandomAuthKey(1)});
  EXPECT_EQ(f.Check(attacker.Sign(Payload())), AuthResult::kBadTag);
  // A key id the receiver does not hold.
  attacker.keys = Ring({RandomAuthKey(9)});
  EXPECT_EQ(f.Check(attacker.Sign(Payload())), AuthResult::kUnknownKey);
  EXPECT_EQ(f.Check(m), AuthResult::kAccepted);
}

TEST(MessageAuth, UnsignedAndMalformedAreRefused) {
  Fixture f;
  EXPECT_EQ(f.Check(Payload()), AuthResult::kUnsigned);
  EXPECT_EQ(f.Check({}), AuthResult::kUnsigned);
  // A trailer with no room for a fingerprint before it.
  const std::vector<uint8_t> tiny = f.Sign(Payload(4));
  EXPECT_EQ(f.Check(tiny), AuthResult::kMalformed);
}

TEST(MessageAuth, ReplayIsRefusedAndReorderingWithinTheWindowAcceptedOnce) {
  Fixture f;
  std::vector<std::vector<uint8_t>> sent;
  for (int i = 0; i < 100; ++i) sent.push_back(f.Sign(Payload(), kNow + i));
  EXPECT_EQ(f.Check(sent[0]), AuthResult::kAccepted);
  EXPECT_EQ(f.Check(sent[0]), AuthResult::kReplayed);
  // Out of order: 70 first, then 10..69 (within 64 of 70 for 7..70) once each.
  EXPECT_EQ(f.Check(sent[70]), AuthResult::kAccepted);
  EXPECT_EQ(f.Check(sent[6]), AuthResult::kReplayed);  // seq 7: 64 behind seq 71, outside the window
  for (int i = 7; i < 70; ++i) {
    EXPECT_EQ(f.Check(sent[i]), AuthResult::kAccepted) << i;
    EXPECT_EQ(f.Check(sent[i]), AuthResult::kReplayed) << i;
  }
  EXPECT_EQ(f.Check(sent[70]), AuthResult::kReplayed);
  EXPECT_EQ(f.Check(sent[99]), AuthResult::kAccepted);
  EXPECT_EQ(f.Check(sent[71]), AuthResult::kAccepted);
}

TEST(MessageAuth, ReplayWindowMatchesABruteForceSet) {
  // Independent reference: a set of every number seen and the rule "fresh if unseen and
  // within 64 of the highest".
  ReplayWindow w;
  std::set<uint64_t> seen;
  uint64_t highest = 0;
  uint32_t state = 12345;
  for (int i = 0; i < 20000; ++i) {
    state = state * 1103515245u + 12345u;
    const uint64_t seq = 1000 + i / 2 + (state >> 16) % 150;  // drifting upwards, jittered
    const bool expected = seen.empty() || seq > highest || (highest - seq < 64 && !seen.count(seq));
    ASSERT_EQ(w.Fresh(seq), expected) << i;
    if (expected) {
      w.Record(seq);
      seen.insert(seq);
      highest = std::max(highest, seq);
    }
  }
}

TEST(MessageAuth, TooOldAndFutureStampsAreRefused) {
  Fixture f;
  EXPECT_EQ(f.Check(f.Sign(Payload(), kNow - 6 * kSecond)), AuthResult::kTooOld);
  EXPECT_EQ(f.Check(f.Sign(Payload(), kNow + 6 * kSecond)), AuthResult::kFromFuture);
  EXPECT_EQ(f.Check(f.Sign(Payload(), -1)), AuthResult::kTooOld);
  EXPECT_EQ(f.Check(f.Sign(Payload(), INT64_MAX)), AuthResult::kFromFuture);
  EXPECT_EQ(f.Check(f.Sign(Payload(), INT64_MIN)), AuthResult::kTooOld);
  EXPECT_EQ(f.Check(f.Sign(Payload(), kNow - 4 * kSecond)), AuthResult::kAccepted);
  EXPECT_EQ(f.Check(f.Sign(Payload(), kNow + 4 * kSecond)), AuthResult::kAccepted);
}

TEST(MessageAuth, RotationAcceptsBothKeysAndThePublisherSwitches) {
  const AuthKey old_key = RandomAuthKey(1), new_key = RandomAuthKey(2);
  MessageSigner signer(RandomSenderId());
  MessageVerifier verifier(5 * kSecond);
  const std::vector<uint8_t> p = Payload();
  auto sign = [&](const AuthKeyRing& ring) {
    return signer.Sign(ring, "DRIVE_PATH", p.data(), static_cast<int>(p.size()), kNow);
  };
  auto check = [&](const AuthKeyRing& ring, const std::vector<uint8_t>& m) {
    return verifier.Verify(ring, "DRIVE_PATH", m.data(), static_cast<int>(m.size()), kNow);
  };
  const AuthKeyRing before = Ring({old_key}), during = Ring({old_key, new_key}), after = Ring({new_key});
  const std::vector<uint8_t> by_old = sign(before);
  const std::vector<uint8_t> by_new = sign(during);
  EXPECT_EQ(check(before, by_old).trailer.key_id, 1u);
  EXPECT_EQ(check(during, by_new).trailer.key_id, 2u);  // the publisher signs with the last key
  MessageVerifier fresh(5 * kSecond);
  EXPECT_EQ(fresh.Verify(during, "DRIVE_PATH", by_old.data(), static_cast<int>(by_old.size()), kNow).result,
            AuthResult::kAccepted);
  EXPECT_EQ(fresh.Verify(during, "DRIVE_PATH", by_new.data(), static_cast<int>(by_new.size()), kNow).result,
            AuthResult::kAccepted);
  const std::vector<uint8_t> late_old = sign(before);
  EXPECT_EQ(fresh.Verify(after, "DRIVE_PATH", late_old.data(), static_cast<int>(late_old.size()), kNow).result,
            AuthResult::kUnknownKey);
}

TEST(MessageAuth, SenderWindowsAreBoundedOldestEvicted) {
  const AuthKeyRing keys = Ring({RandomAuthKey(1)});
  MessageVerifier verifier(5 * kSecond, /*max_senders=*/4);
  const std::vector<uint8_t> p = Payload();
  std::vector<std::vector<uint8_t>> first;
  for (int s = 0; s < 6; ++s) {
    MessageSigner signer(static_cast<uint64_t>(s + 1));
    first.push_back(signer.Sign(keys, "C", p.data(), static_cast<int>(p.size()), kNow));
    EXPECT_EQ(verifier.Verify(keys, "C", first.back().data(), static_cast<int>(first.back().size()), kNow).result,
              AuthResult::kAccepted);
  }
  EXPECT_EQ(verifier.senders_tracked(), 4);
  // The latest senders' windows are kept.
  EXPECT_EQ(verifier.Verify(keys, "C", first[5].data(), static_cast<int>(first[5].size()), kNow).result,
            AuthResult::kReplayed);
}

TEST(MessageAuth, KeyTextParsesAndRefusesMalformedLines) {
  const AuthKey k1 = RandomAuthKey(1), k7 = RandomAuthKey(7);
  const AuthKeyRing ring = ParseAuthKeys("# comment\n\n" + FormatAuthKey(k1) + "\n" + FormatAuthKey(k7) + "\n", "f");
  ASSERT_EQ(ring.keys.size(), 2u);
  EXPECT_EQ(ring.signing_key().id, 7u);
  EXPECT_EQ(ring.keys[0].bytes, k1.bytes);
  EXPECT_EQ(ring.Find(7)->bytes, k7.bytes);
  const std::string hex = FormatAuthKey(k1).substr(2);
  for (const std::string& bad : std::vector<std::string>{"", "# only a comment\n", "1\n", "x " + hex,
                                 "-1 " + hex, "4294967296 " + hex, "1 " + hex.substr(1), "1 " + hex + "0",
                                 "1 " + hex.substr(0, 63) + "g", "1 " + hex + " extra",
                                 "1 " + hex + "\n1 " + hex}) {
    EXPECT_THROW(ParseAuthKeys(bad, "f"), InputError) << bad;
  }
}

}  // namespace
}  // namespace minenav
