#pragma once
// A Bus that signs and verifies the command channels (issue 16, "Security"; the trailer and
// its checks in common/message_auth.h, the key file in common/auth_key_file.h). It decorates
// the bus a process would use otherwise (LcmBus, LogBus, FakeBus): on the signed channels it
// appends a trailer to every publication and, before any handler (and so before anything
// decodes), verifies and strips the trailer of every message received; a message that fails is
// never handed on: it is counted in messages_bad and auth_rejected and logged in one line
// naming the channel and the reason (rate-limited as every bad message, Bus::ReportBad). Other
// channels pass untouched. NodeRuntime wraps its bus in one when --auth.key-file is given.
//
// Limitation: a process subscribes to a signed channel once. LCM hands one receipt to every
// matching subscription, and the second delivery of the same message is refused as a replay
// (no node of the fleet subscribes twice to a signed channel; telling a second delivery from a
// replay would need a receipt id from the transport).

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/auth_key_file.h"
#include "common/clock.h"
#include "common/config.h"
#include "common/message_auth.h"
#include "common/node/bus.h"

namespace minenav {

struct AuthOptions {
  std::string key_file;  // "" = no authentication
  // Comma-separated channel names that are signed and must verify.
  std::string signed_channels =
      "DRIVE_COMMAND,CUTTER_COMMAND,COORDINATOR_COMMAND,PATH_REQUEST,PATH,TASK_REQUEST,TASK_PLAN,CUT_TASK,DRIVE_PATH";
  double max_age = 5.0;  // s: a signed message stamped further than this from its receive time is refused
};
// Declares the options in `scope` (NodeRuntime: "auth", so --auth.key-file, --auth.signed-channels,
// --auth.max-age).
void DeclareOptions(OptionScope scope, AuthOptions& options);
// The channel names of `list` (comma-separated); throws UsageError on an empty name.
std::set<std::string, std::less<>> ParseChannelList(const std::string& list);

class AuthBus final : public Bus {
 public:
  // Loads the key file (throws InputError when it is refused); `clock` stamps publications and
  // paces the key file's re-reading.
  AuthBus(std::unique_ptr<Bus> inner, const AuthOptions& options, const Clock& clock);

  bool Publish(const std::string& channel, const void* data, int size) override;
  void Subscribe(const std::string& channel, RawHandler handler) override;
  int HandleFor(int64_t timeout_us) override;

  bool IsSigned(std::string_view channel) const { return signed_channels_.count(channel) != 0; }
  Bus& inner() { return *inner_; }
  const AuthKeyRing& keys() const { return watcher_.keys(); }
  uint64_t sender() const { return signer_.sender(); }

 private:
  void PollKeyFile();
  // Verifies `raw` (on a signed channel); true and `out` the stripped message when accepted.
  bool Verify(const RawMessage& raw, RawMessage* out);

  std::unique_ptr<Bus> inner_;
  const Clock& clock_;
  // The handlers of each subscribed pattern: one inner subscription per pattern verifies a
  // message once and hands it to all of them (a second verification would see a replay).
  std::map<std::string, std::unique_ptr<std::vector<RawHandler>>, std::less<>> handlers_;
  std::set<std::string, std::less<>> signed_channels_;
  AuthKeyFileWatcher watcher_;
  std::string reported_key_error_;
  MessageSigner signer_;
  MessageVerifier verifier_;
};

}  // namespace minenav
