#pragma once
// The key file of message authentication (common/message_auth.h): text, one key per line,
// `KEY_ID HEX64`; the last line's key signs, every listed key verifies. It must be readable and
// writable by its owner only (mode & 077 == 0): a key others can read authenticates nothing.
// A running process re-reads it when it changes (AuthKeyFileWatcher), so a key is rotated
// without stopping the fleet: add the new key as the first line everywhere (auth_keygen --add:
// accepted, not signing), wait until every process has re-read the file (a second or two), move
// it last (--sign-newest: it signs), wait, drop the old one (--keep-last).

#include <cstdint>
#include <string>

#include "common/message_auth.h"

namespace minenav {

// Reads and parses `path`. Throws InputError (one line) when it cannot be read, is not a
// regular file, is readable or writable by group or others, or is malformed.
AuthKeyRing LoadAuthKeyFile(const std::string& path);
// Writes `keys` to `path` (mode 0600, atomically).
void SaveAuthKeyFile(const std::string& path, const AuthKeyRing& keys);

// Re-reads a key file when its modification time, size or inode changed, at most once per
// `check_period_us` of the caller's clock.
class AuthKeyFileWatcher {
 public:
  // Loads the file (throws InputError as LoadAuthKeyFile).
  explicit AuthKeyFileWatcher(std::string path, int64_t check_period_us = 1'000'000);
  // Looks at the file if `now_us` is a period after the last look; returns true when the keys
  // changed. A file that became unreadable, too open or malformed keeps the keys held and
  // sets error() (a rotation half written must not lock the fleet out).
  bool Poll(int64_t now_us);
  const AuthKeyRing& keys() const { return keys_; }
  const std::string& path() const { return path_; }
  const std::string& error() const { return error_; }

 private:
  struct Stamp {
    int64_t mtime_ns = 0;
    int64_t size = -1;
    uint64_t inode = 0;  // an atomic rewrite (rename) is a new inode even within one mtime tick
    bool operator==(const Stamp&) const = default;
  };
  static Stamp StampOf(const std::string& path);
  std::string path_;
  int64_t check_period_us_;
  int64_t last_check_us_ = 0;
  bool checked_once_ = false;
  Stamp stamp_;
  AuthKeyRing keys_;
  std::string error_;
};

}  // namespace minenav
