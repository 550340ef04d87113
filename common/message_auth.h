#pragma once
// Message authentication of the fleet's command channels (issue 16, "Security"): an
// HMAC-SHA256 trailer appended AFTER a message's LCM encoding, so tools that know nothing of it
// (lcm-logger, lcm-spy) still carry and record the message, and readers that decode it simply
// ignore or strip the trailer (StripAuthTrailer). No LCM, no clock, no I/O: times are given.
//
// Trailer (64 bytes, big-endian like LCM), after the payload:
//   key_id u32 | sender u64 | seq u64 | utime i64 | tag[32] | magic u32 "MNA1"
// tag = HMAC-SHA256(key[key_id], domain | key_id | sender | seq | utime | len(channel) |
//                   channel | payload), the payload beginning with the type's 8-byte
//       fingerprint, so a tag made for one channel or type is worth nothing on another.
// The magic comes last so a reader finds the trailer from the end of the bytes.
//
// The receiver (MessageVerifier) checks, in this order and before anything decodes the
// payload: a trailer is there (else kUnsigned), the key id is known (kUnknownKey), the tag, in
// constant time (crypto_verify_32, what crypto_auth_hmacsha256_verify does; kBadTag), the
// sender's stamp within max_age of the receive time either way (kTooOld, kFromFuture), and the
// sequence number against the sender's replay window (kReplayed): the highest number seen and
// a 64-entry bitmap below it, as IPsec's anti-replay window (RFC 4303, section 3.4.3), so a
// message reordered by at most 64 is still accepted, once. Senders are 64-bit random numbers
// drawn per process; at most `max_senders` windows are kept, the least recently heard from
// evicted first.
//
// HMAC: RFC 2104; SHA-256 and the constant-time comparison from libsodium (Debian
// libsodium-dev).

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace minenav {

inline constexpr int kAuthKeyBytes = 32;
inline constexpr int kAuthTagBytes = 32;
inline constexpr int kAuthTrailerBytes = 4 + 8 + 8 + 8 + kAuthTagBytes + 4;
inline constexpr uint32_t kAuthTrailerMagic = 0x4D4E4131;  // "MNA1"
// The LCM type fingerprint every payload begins with.
inline constexpr int kAuthFingerprintBytes = 8;
// Width of the replay window (messages).
inline constexpr int kReplayWindow = 64;

struct AuthKey {
  uint32_t id = 0;
  std::array<uint8_t, kAuthKeyBytes> bytes{};
};

// The keys a process holds: it signs with the last one and accepts all of them (so a new key
// can be added everywhere before any publisher uses it, and the old one removed later).
struct AuthKeyRing {
  std::vector<AuthKey> keys;
  const AuthKey* Find(uint32_t id) const;
  const AuthKey& signing_key() const { return keys.back(); }
};

// Parses a key file's text: one key per line, `KEY_ID HEX64` (KEY_ID a decimal number below
// 2^32, HEX64 the 32-byte key in 64 hex digits); blank lines and lines starting with '#' are
// ignored. Throws InputError naming `source_name` and the line for anything else, for a
// repeated key id, and for a file without keys.
AuthKeyRing ParseAuthKeys(const std::string& text, const std::string& source_name);
// One line of a key file for `key`.
std::string FormatAuthKey(const AuthKey& key);

enum class AuthResult {
  kAccepted,
  kUnsigned,     // no trailer
  kMalformed,    // a trailer but no room for the type's fingerprint before it
  kUnknownKey,   // signed with a key id this process does not hold
  kBadTag,       // forged, tampered with, wrong key, or signed for another channel
  kReplayed,     // a sequence number of this sender seen before, or below its window
  kTooOld,       // stamped more than max_age before its receive time
  kFromFuture,   // stamped more than max_age after its receive time
};
const char* AuthResultName(AuthResult result);

// The fields of a trailer (parsed, not yet verified).
struct AuthTrailer {
  uint32_t key_id = 0;
  uint64_t sender = 0;
  uint64_t seq = 0;
  int64_t utime = 0;
  std::array<uint8_t, kAuthTagBytes> tag{};
};

// Bytes of `data` that are the LCM message: `size` without a trailer, size - 64 with one.
// The one way readers of logs (which may hold signed messages) find the payload.
int StripAuthTrailer(const uint8_t* data, int size);
// True and the trailer's fields when the last bytes of `data` are a trailer.
bool ParseAuthTrailer(const uint8_t* data, int size, AuthTrailer* trailer);

// The tag of `payload` on `channel` under `key` and the trailer's other fields.
std::array<uint8_t, kAuthTagBytes> ComputeAuthTag(const AuthKey& key, const AuthTrailer& fields,
                                                  std::string_view channel, const uint8_t* payload, int size);

// The publishing side: one per process, one sequence over all its signed channels.
class MessageSigner {
 public:
  // `sender`: the process's random id (RandomSenderId()).
  explicit MessageSigner(uint64_t sender) : sender_(sender) {}
  // `payload` with its trailer appended, stamped `utime` (us), signed with the ring's last key.
  std::vector<uint8_t> Sign(const AuthKeyRing& keys, std::string_view channel, const uint8_t* payload, int size,
                            int64_t utime);
  uint64_t sender() const { return sender_; }
  uint64_t next_seq() const { return next_seq_; }

 private:
  uint64_t sender_;
  uint64_t next_seq_ = 1;
};

// A fresh random sender id (libsodium's randombytes_buf).
uint64_t RandomSenderId();
// A fresh random key (randombytes_buf).
AuthKey RandomAuthKey(uint32_t id);

// IPsec-style anti-replay window of one sender.
class ReplayWindow {
 public:
  // True when `seq` was not seen and is not below the window; does not record it.
  bool Fresh(uint64_t seq) const;
  // Records `seq` (call only after Fresh(seq) and the tag was checked).
  void Record(uint64_t seq);

 private:
  uint64_t highest_ = 0;
  uint64_t seen_ = 0;  // bit i: highest_ - i was seen
  bool any_ = false;
};

struct VerifyOutcome {
  AuthResult result = AuthResult::kUnsigned;
  int payload_size = 0;  // the LCM message's bytes when accepted
  AuthTrailer trailer;   // parsed fields (meaningful from kUnknownKey on)
};

class MessageVerifier {
 public:
  // `max_age_us`: how far a stamp may be from the receive time, either way (> 0).
  // `max_senders`: replay windows kept (the least recently accepted sender evicted first).
  explicit MessageVerifier(int64_t max_age_us, int max_senders = 256)
      : max_age_us_(max_age_us), max_senders_(max_senders) {}
  // Verifies `data` (payload + trailer) received on `channel` at `receive_utime` (us) against
  // `keys`; on kAccepted the sender's window records the sequence number.
  VerifyOutcome Verify(const AuthKeyRing& keys, std::string_view channel, const uint8_t* data, int size,
                       int64_t receive_utime);
  int senders_tracked() const { return static_cast<int>(windows_.size()); }

 private:
  struct SenderState {
    ReplayWindow window;
    uint64_t last_use = 0;
  };
  int64_t max_age_us_;
  int max_senders_;
  uint64_t use_counter_ = 0;
  std::map<uint64_t, SenderState> windows_;
};

}  // namespace minenav
