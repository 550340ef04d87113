#include "common/message_auth.h"

#include <sodium.h>

#include <cctype>
#include <sstream>
#include <stdexcept>

#include "common/file_io.h"

namespace minenav {

namespace {

// Distinguishes these tags from any other HMAC made with the same key.
constexpr std::string_view kDomain = "minenav-auth-v1";

void InitSodium() {
  // Idempotent and thread-safe; fails only when the system has no entropy source.
  if (sodium_init() < 0) throw std::runtime_error("libsodium failed to initialise (no entropy source?)");
}

void PutU32(uint8_t* out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}
void PutU64(uint8_t* out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out[i] = static_cast<uint8_t>(v >> (56 - 8 * i));
}
uint32_t GetU32(const uint8_t* in) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | in[i];
  return v;
}
uint64_t GetU64(const uint8_t* in) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v = (v << 8) | in[i];
  return v;
}

// key_id | sender | seq | utime: the trailer's first 28 bytes, also what the tag covers.
constexpr int kFieldBytes = 4 + 8 + 8 + 8;
void PutFields(uint8_t* out, const AuthTrailer& t) {
  PutU32(out, t.key_id);
  PutU64(out + 4, t.sender);
  PutU64(out + 12, t.seq);
  PutU64(out + 20, static_cast<uint64_t>(t.utime));
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

const AuthKey* AuthKeyRing::Find(uint32_t id) const {
  for (const AuthKey& k : keys)
    if (k.id == id) return &k;
  return nullptr;
}

AuthKeyRing ParseAuthKeys(const std::string& text, const std::string& source_name) {
  AuthKeyRing ring;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::string where = source_name + " line " + std::to_string(number);
    size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    std::istringstream fields(line);
    std::string id_text, hex, extra;
    fields >> id_text >> hex;
    if (id_text.empty() || hex.empty() || (fields >> extra))
      throw InputError(where + ": expected 'KEY_ID HEX64' (a key id and a 64-hex-digit key)");
    if (id_text.size() > 10 || id_text.find_first_not_of("0123456789") != std::string::npos ||
        std::stoull(id_text) > 0xFFFFFFFFull)
      throw InputError(where + ": key id '" + id_text + "' is not a number from 0 to 4294967295");
    if (hex.size() != 2 * kAuthKeyBytes)
      throw InputError(where + ": the key has " + std::to_string(hex.size()) + " hex digits, expected " +
                       std::to_string(2 * kAuthKeyBytes));
    AuthKey key;
    key.id = static_cast<uint32_t>(std::stoull(id_text));
    for (int i = 0; i < kAuthKeyBytes; ++i) {
      const int hi = HexDigit(hex[2 * i]), lo = HexDigit(hex[2 * i + 1]);
      if (hi < 0 || lo < 0) throw InputError(where + ": the key is not hexadecimal");
      key.bytes[i] = static_cast<uint8_t>(hi * 16 + lo);
    }
    if (ring.Find(key.id) != nullptr) throw InputError(where + ": key id " + id_text + " appears twice");
    ring.keys.push_back(key);
  }
  if (ring.keys.empty()) throw InputError(source_name + ": no key (expected lines 'KEY_ID HEX64')");
  return ring;
}

std::string FormatAuthKey(const AuthKey& key) {
  static const char kHex[] = "0123456789abcdef";
  std::string out = std::to_string(key.id) + " ";
  for (uint8_t b : key.bytes) {
    out += kHex[b >> 4];
    out += kHex[b & 15];
  }
  return out;
}

const char* AuthResultName(AuthResult result) {
  switch (result) {
    case AuthResult::kAccepted: return "accepted";
    case AuthResult::kUnsigned: return "unsigned";
    case AuthResult::kMalformed: return "malformed";
    case AuthResult::kUnknownKey: return "unknown key id";
    case AuthResult::kBadTag: return "bad tag";
    case AuthResult::kReplayed: return "replayed";
    case AuthResult::kTooOld: return "too old";
    case AuthResult::kFromFuture: return "stamped in the future";
  }
  return "?";
}

bool ParseAuthTrailer(const uint8_t* data, int size, AuthTrailer* trailer) {
  if (data == nullptr || size < kAuthTrailerBytes) return false;
  const uint8_t* t = data + size - kAuthTrailerBytes;
  if (GetU32(t + kAuthTrailerBytes - 4) != kAuthTrailerMagic) return false;
  trailer->key_id = GetU32(t);
  trailer->sender = GetU64(t + 4);
  trailer->seq = GetU64(t + 12);
  trailer->utime = static_cast<int64_t>(GetU64(t + 20));
  std::copy(t + kFieldBytes, t + kFieldBytes + kAuthTagBytes, trailer->tag.begin());
  return true;
}

int StripAuthTrailer(const uint8_t* data, int size) {
  AuthTrailer unused;
  return ParseAuthTrailer(data, size, &unused) ? size - kAuthTrailerBytes : size;
}

std::array<uint8_t, kAuthTagBytes> ComputeAuthTag(const AuthKey& key, const AuthTrailer& fields,
                                                  std::string_view channel, const uint8_t* payload, int size) {
  InitSodium();
  crypto_auth_hmacsha256_state state;
  crypto_auth_hmacsha256_init(&state, key.bytes.data(), key.bytes.size());
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const uint8_t*>(kDomain.data()), kDomain.size());
  uint8_t head[kFieldBytes + 4];
  PutFields(head, fields);
  PutU32(head + kFieldBytes, static_cast<uint32_t>(channel.size()));
  crypto_auth_hmacsha256_update(&state, head, sizeof(head));
  crypto_auth_hmacsha256_update(&state, reinterpret_cast<const uint8_t*>(channel.data()), channel.size());
  crypto_auth_hmacsha256_update(&state, payload, static_cast<unsigned long long>(size));
  std::array<uint8_t, kAuthTagBytes> tag{};
  crypto_auth_hmacsha256_final(&state, tag.data());
  sodium_memzero(&state, sizeof(state));
  return tag;
}

std::vector<uint8_t> MessageSigner::Sign(const AuthKeyRing& keys, std::string_view channel, const uint8_t* payload,
                                         int size, int64_t utime) {
  if (keys.keys.empty()) throw std::logic_error("MessageSigner::Sign without a key");
  AuthTrailer t;
  t.key_id = keys.signing_key().id;
  t.sender = sender_;
  t.seq = next_seq_++;
  t.utime = utime;
  t.tag = ComputeAuthTag(keys.signing_key(), t, channel, payload, size);
  std::vector<uint8_t> out(payload, payload + size);
  out.resize(static_cast<size_t>(size) + kAuthTrailerBytes);
  uint8_t* p = out.data() + size;
  PutFields(p, t);
  std::copy(t.tag.begin(), t.tag.end(), p + kFieldBytes);
  PutU32(p + kFieldBytes + kAuthTagBytes, kAuthTrailerMagic);
  return out;
}

uint64_t RandomSenderId() {
  InitSodium();
  uint64_t id = 0;
  randombytes_buf(&id, sizeof(id));
  return id;
}

AuthKey RandomAuthKey(uint32_t id) {
  InitSodium();
  AuthKey key;
  key.id = id;
  randombytes_buf(key.bytes.data(), key.bytes.size());
  return key;
}

bool ReplayWindow::Fresh(uint64_t seq) const {
  if (!any_ || seq > highest_) return true;
  const uint64_t behind = highest_ - seq;
  if (behind >= kReplayWindow) return false;  // too far behind to tell: refused
  return ((seen_ >> behind) & 1u) == 0;
}

void ReplayWindow::Record(uint64_t seq) {
  if (!any_) {
    any_ = true;
    highest_ = seq;
    seen_ = 1;
    return;
  }
  if (seq > highest_) {
    const uint64_t ahead = seq - highest_;
    seen_ = ahead >= kReplayWindow ? 0 : seen_ << ahead;
    seen_ |= 1;
    highest_ = seq;
    return;
  }
  seen_ |= uint64_t{1} << (highest_ - seq);
}

VerifyOutcome MessageVerifier::Verify(const AuthKeyRing& keys, std::string_view channel, const uint8_t* data,
                                      int size, int64_t receive_utime) {
  VerifyOutcome out;
  if (!ParseAuthTrailer(data, size, &out.trailer)) {
    out.result = AuthResult::kUnsigned;
    return out;
  }
  const int payload_size = size - kAuthTrailerBytes;
  if (payload_size < kAuthFingerprintBytes) {
    out.result = AuthResult::kMalformed;
    return out;
  }
  const AuthKey* key = keys.Find(out.trailer.key_id);
  if (key == nullptr) {
    out.result = AuthResult::kUnknownKey;
    return out;
  }
  const std::array<uint8_t, kAuthTagBytes> expected = ComputeAuthTag(*key, out.trailer, channel, data, payload_size);
  // Constant time: how many bytes of a forged tag are right leaks nothing.
  if (crypto_verify_32(expected.data(), out.trailer.tag.data()) != 0) {
    out.result = AuthResult::kBadTag;
    return out;
  }
  // Written so that no subtraction overflows whatever the stamps are.
  const int64_t stamp = out.trailer.utime;
  if (stamp < receive_utime && (stamp < 0 || receive_utime - stamp > max_age_us_)) {
    out.result = AuthResult::kTooOld;
    return out;
  }
  if (stamp > receive_utime && (receive_utime < 0 || stamp - receive_utime > max_age_us_)) {
    out.result = AuthResult::kFromFuture;
    return out;
  }
  auto it = windows_.find(out.trailer.sender);
  if (it != windows_.end() && !it->second.window.Fresh(out.trailer.seq)) {
    out.result = AuthResult::kReplayed;
    return out;
  }
  if (it == windows_.end()) {
    if (static_cast<int>(windows_.size()) >= max_senders_) {
      auto oldest = windows_.begin();
      for (auto w = windows_.begin(); w != windows_.end(); ++w)
        if (w->second.last_use < oldest->second.last_use) oldest = w;
      windows_.erase(oldest);
    }
    it = windows_.emplace(out.trailer.sender, SenderState{}).first;
  }
  it->second.window.Record(out.trailer.seq);
  it->second.last_use = ++use_counter_;
  out.result = AuthResult::kAccepted;
  out.payload_size = payload_size;
  return out;
}

}  // namespace minenav
