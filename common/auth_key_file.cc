#include "common/auth_key_file.h"

#include <sys/stat.h>

#include <cstdio>

#include "common/file_io.h"

namespace minenav {

namespace {

// Checks the mode before the content is read: a key others can read is refused even if valid.
void CheckKeyFileMode(const std::string& path, const struct stat& st) {
  if (!S_ISREG(st.st_mode)) throw InputError("key file " + path + " is not a regular file");
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", static_cast<unsigned>(st.st_mode & 07777));
    throw InputError("key file " + path + " is readable or writable by group or others (mode " + mode +
                     "): chmod 600 " + path);
  }
}

}  // namespace

AuthKeyRing LoadAuthKeyFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError("key file " + path + " cannot be read");
  CheckKeyFileMode(path, st);
  return ParseAuthKeys(ReadFile(path), "key file " + path);
}

void SaveAuthKeyFile(const std::string& path, const AuthKeyRing& keys) {
  std::string text = "# KEY_ID HEX64: the last key signs, every key verifies (common/auth_key_file.h)\n";
  for (const AuthKey& k : keys.keys) text += FormatAuthKey(k) + "\n";
  WriteFileAtomically(path, text, {.mode = 0600});
}

AuthKeyFileWatcher::AuthKeyFileWatcher(std::string path, int64_t check_period_us)
    : path_(std::move(path)), check_period_us_(check_period_us) {
  stamp_ = StampOf(path_);
  keys_ = LoadAuthKeyFile(path_);
}

AuthKeyFileWatcher::Stamp AuthKeyFileWatcher::StampOf(const std::string& path) {
  struct stat st {};
  Stamp s;
  if (::stat(path.c_str(), &st) != 0) return s;
  s.mtime_ns = static_cast<int64_t>(st.st_mtim.tv_sec) * 1'000'000'000 + st.st_mtim.tv_nsec;
  s.size = static_cast<int64_t>(st.st_size);
  s.inode = static_cast<uint64_t>(st.st_ino);
  return s;
}

bool AuthKeyFileWatcher::Poll(int64_t now_us) {
  if (checked_once_ && now_us >= last_check_us_ && now_us - last_check_us_ < check_period_us_) return false;
  checked_once_ = true;
  last_check_us_ = now_us;
  const Stamp stamp = StampOf(path_);
  if (stamp == stamp_) return false;
  stamp_ = stamp;
  try {
    keys_ = LoadAuthKeyFile(path_);
    error_.clear();
    return true;
  } catch (const InputError& e) {
    error_ = std::string(e.what()) + " (the previous keys stay in use)";
    return false;
  }
}

}  // namespace minenav
