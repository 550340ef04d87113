#include "common/node/auth_bus.h"

#include <cmath>
#include <sstream>

#include "common/log.h"

namespace minenav {

void DeclareOptions(OptionScope scope, AuthOptions& o) {
  scope.AddString("key_file", &o.key_file,
                  "key file (lines 'KEY_ID HEX64', mode 600; auth_keygen writes one): sign the signed channels "
                  "and refuse what does not verify on them; empty = no authentication");
  scope.AddString("signed_channels", &o.signed_channels,
                  "comma-separated channels signed and verified when a key file is given");
  scope.AddDouble("max_age", &o.max_age, "s",
                  "refuse a signed message stamped further than this from its receive time, either way "
                  "(clock skew plus delivery delay)",
                  0.01, 3600.0);
}

std::set<std::string, std::less<>> ParseChannelList(const std::string& list) {
  std::set<std::string, std::less<>> out;
  std::istringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    const size_t b = name.find_first_not_of(' '), e = name.find_last_not_of(' ');
    if (b == std::string::npos) throw UsageError("--auth.signed-channels: empty channel name in '" + list + "'");
    out.insert(name.substr(b, e - b + 1));
  }
  return out;
}

AuthBus::AuthBus(std::unique_ptr<Bus> inner, const AuthOptions& options, const Clock& clock)
    : inner_(std::move(inner)),
      clock_(clock),
      signed_channels_(ParseChannelList(options.signed_channels)),
      watcher_(options.key_file),
      signer_(RandomSenderId()),
      verifier_(static_cast<int64_t>(std::llround(options.max_age * 1e6))) {
  MINENAV_LOG(kInfo) << "authentication on " << signed_channels_.size() << " channel(s) with " << options.key_file
                     << " (signing key id " << watcher_.keys().signing_key().id << ", "
                     << watcher_.keys().keys.size() << " key(s) accepted)";
}

void AuthBus::PollKeyFile() {
  if (watcher_.Poll(clock_.NowUtime())) {
    reported_key_error_.clear();
    MINENAV_LOG(kInfo) << "key file " << watcher_.path() << " re-read: signing key id "
                       << watcher_.keys().signing_key().id << ", " << watcher_.keys().keys.size()
                       << " key(s) accepted";
  } else if (!watcher_.error().empty() && watcher_.error() != reported_key_error_) {
    reported_key_error_ = watcher_.error();
    MINENAV_LOG(kWarn) << reported_key_error_;
  }
}

bool AuthBus::Publish(const std::string& channel, const void* data, int size) {
  bool ok = false;
  if (IsSigned(channel) && data != nullptr && size >= 0) {
    PollKeyFile();
    const std::vector<uint8_t> signed_bytes =
        signer_.Sign(watcher_.keys(), channel, static_cast<const uint8_t*>(data), size, clock_.NowUtime());
    ok = inner_->Publish(channel, signed_bytes.data(), static_cast<int>(signed_bytes.size()));
  } else {
    ok = inner_->Publish(channel, data, size);
  }
  CountPublished(ok, channel);
  return ok;
}

bool AuthBus::Verify(const RawMessage& raw, RawMessage* out) {
  PollKeyFile();
  const VerifyOutcome v = verifier_.Verify(watcher_.keys(), raw.channel, raw.data, raw.size, raw.utime);
  if (v.result == AuthResult::kAccepted) {
    *out = raw;
    out->size = v.payload_size;
    return true;
  }
  std::string why = "channel " + std::string(raw.channel) + ": refused by authentication: " + AuthResultName(v.result);
  if (v.result != AuthResult::kUnsigned && v.result != AuthResult::kMalformed) {
    std::ostringstream detail;
    detail << " (key id " << v.trailer.key_id << ", sender " << std::hex << v.trailer.sender << std::dec << ", seq "
           << v.trailer.seq;
    if (v.result == AuthResult::kTooOld || v.result == AuthResult::kFromFuture)
      detail << ", stamped " << (v.trailer.utime - raw.utime) / 1000 << " ms from its receive time";
    detail << ")";
    why += detail.str();
  }
  ReportUnauthenticated(raw.channel, why);
  return false;
}

void AuthBus::Subscribe(const std::string& channel, RawHandler handler) {
  auto [it, first] = handlers_.try_emplace(channel);
  if (!first) {
    it->second->push_back(std::move(handler));
    return;
  }
  it->second = std::make_unique<std::vector<RawHandler>>(1, std::move(handler));
  inner_->Subscribe(channel, [this, &handlers = *it->second](const RawMessage& raw) {
    RawMessage message = raw;
    if (IsSigned(raw.channel) && !Verify(raw, &message)) return;
    // Caught here so the failure is counted on this bus (the one HEARTBEAT reports), not the inner one.
    for (size_t i = 0; i < handlers.size(); ++i) {  // by index: a handler may subscribe another
      try {
        handlers[i](message);
      } catch (const std::exception& e) {
        ReportBad(raw.channel, "channel " + std::string(raw.channel) + ": handler failed: " + e.what());
      }
    }
  });
}

int AuthBus::HandleFor(int64_t timeout_us) { return inner_->HandleFor(timeout_us); }

}  // namespace minenav
