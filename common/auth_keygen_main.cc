// auth_keygen: writes and rotates the fleet's key file (common/auth_key_file.h).
//
//   auth_keygen FILE                a new file with one fresh key (id 1); refuses to overwrite
//   auth_keygen --add FILE          a fresh key (the next id) as the FIRST line: accepted, not yet signing
//   auth_keygen --sign-newest FILE  moves the newest key (highest id) to the last line: it signs
//   auth_keygen --keep-last FILE    removes every key but the last
//
// A rotation without a refused command: --add, wait until every process re-read the file (it
// looks once a second), --sign-newest, wait, --keep-last. Each step keeps the key every
// not-yet-updated publisher signs with accepted by every receiver, updated or not.
//
// Keys come from libsodium's randombytes_buf; the file is written atomically with mode 0600.

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "common/auth_key_file.h"
#include "common/config.h"
#include "common/file_io.h"

namespace {

constexpr const char* kUsage =
    "usage: auth_keygen [--add | --sign-newest | --keep-last] FILE\n"
    "  FILE                 writes a new key file (mode 600) with one fresh 32-byte key, id 1\n"
    "  --add FILE           a fresh key with the next id as the first line (accepted, not signing yet)\n"
    "  --sign-newest FILE   moves the newest key to the last line (it signs)\n"
    "  --keep-last FILE     keeps only the last key (ends a rotation)\n"
    "rotation: --add, wait 2 s, --sign-newest, wait 2 s, --keep-last\n";

}  // namespace

int main(int argc, char** argv) {
  using namespace minenav;
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  const bool add = argc == 3 && std::strcmp(argv[1], "--add") == 0;
  const bool keep_last = argc == 3 && std::strcmp(argv[1], "--keep-last") == 0;
  const bool sign_newest = argc == 3 && std::strcmp(argv[1], "--sign-newest") == 0;
  if (!(argc == 2 && argv[1][0] != '-') && !add && !keep_last && !sign_newest) {
    std::fputs(kUsage, stderr);
    return kExitUsage;
  }
  const std::string path = argv[argc - 1];
  try {
    AuthKeyRing ring;
    if (add || keep_last || sign_newest) {
      ring = LoadAuthKeyFile(path);
    } else {
      struct stat st {};
      if (::stat(path.c_str(), &st) == 0) throw InputError(path + " exists: use --add to rotate its key");
    }
    if (keep_last) {
      ring.keys.erase(ring.keys.begin(), ring.keys.end() - 1);
    } else if (sign_newest) {
      auto newest = std::max_element(ring.keys.begin(), ring.keys.end(),
                                     [](const AuthKey& a, const AuthKey& b) { return a.id < b.id; });
      std::rotate(newest, newest + 1, ring.keys.end());
    } else {
      uint32_t next_id = 1;
      for (const AuthKey& k : ring.keys) next_id = std::max(next_id, k.id + 1);
      ring.keys.insert(ring.keys.begin(), RandomAuthKey(next_id));
    }
    SaveAuthKeyFile(path, ring);
    std::printf("%s: %zu key(s), signing with key id %u\n", path.c_str(), ring.keys.size(),
                ring.signing_key().id);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "auth_keygen: %s\n", e.what());
    return kExitUsage;
  }
}
