#include "common/auth_key_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <thread>

#include "common/file_io.h"
#include "tests/temp_dir.h"

namespace minenav {
namespace {

void WriteWithMode(const std::string& path, const std::string& text, mode_t mode) {
  { std::ofstream(path) << text; }
  ::chmod(path.c_str(), mode);
}

TEST(AuthKeyFile, SavedFileHasMode600AndLoads) {
  testing::TempDir dir("auth_key_file");
  const std::string path = dir / "fleet.key";
  const AuthKeyRing ring{{RandomAuthKey(1), RandomAuthKey(2)}};
  SaveAuthKeyFile(path, ring);
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const AuthKeyRing back = LoadAuthKeyFile(path);
  ASSERT_EQ(back.keys.size(), 2u);
  EXPECT_EQ(back.keys[1].bytes, ring.keys[1].bytes);
}

TEST(AuthKeyFile, OpenPermissionsMissingAndMalformedAreRefused) {
  testing::TempDir dir("auth_key_file");
  const std::string path = dir / "fleet.key";
  const std::string good = FormatAuthKey(RandomAuthKey(1)) + "\n";
  for (mode_t mode : {0640, 0604, 0620, 0602, 0660, 0644}) {
    WriteWithMode(path, good, mode);
    try {
      LoadAuthKeyFile(path);
      ADD_FAILURE() << "mode " << std::oct << mode << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("chmod 600"), std::string::npos) << e.what();
    }
  }
  WriteWithMode(path, good, 0400);
  EXPECT_EQ(LoadAuthKeyFile(path).keys.size(), 1u);
  WriteWithMode(path, "1 abc\n", 0600);
  EXPECT_THROW(LoadAuthKeyFile(path), InputError);
  EXPECT_THROW(LoadAuthKeyFile(dir / "missing.key"), InputError);
  EXPECT_THROW(LoadAuthKeyFile(dir.path().string()), InputError);  // a folder
}

TEST(AuthKeyFile, WatcherRereadsAChangedFileAtMostOncePerPeriodAndKeepsKeysOnABadOne) {
  testing::TempDir dir("auth_key_file");
  const std::string path = dir / "fleet.key";
  const AuthKey k1 = RandomAuthKey(1), k2 = RandomAuthKey(2);
  SaveAuthKeyFile(path, AuthKeyRing{{k1}});
  AuthKeyFileWatcher watcher(path, /*check_period_us=*/1'000'000);
  EXPECT_EQ(watcher.keys().signing_key().id, 1u);
  EXPECT_FALSE(watcher.Poll(0));  // first look: unchanged
  SaveAuthKeyFile(path, AuthKeyRing{{k1, k2}});
  EXPECT_FALSE(watcher.Poll(500'000));  // within the period: not looked at
  EXPECT_TRUE(watcher.Poll(1'000'000));
  EXPECT_EQ(watcher.keys().signing_key().id, 2u);
  EXPECT_EQ(watcher.keys().keys.size(), 2u);
  // Made readable by others: refused, the keys held stay.
  ::chmod(path.c_str(), 0644);
  SaveAuthKeyFile(path, AuthKeyRing{{k2}});  // rewritten (new mtime) ...
  ::chmod(path.c_str(), 0644);               // ... and opened up
  EXPECT_FALSE(watcher.Poll(2'000'000));
  EXPECT_NE(watcher.error().find("group or others"), std::string::npos) << watcher.error();
  EXPECT_EQ(watcher.keys().keys.size(), 2u);
  // Fixed: re-read.
  SaveAuthKeyFile(path, AuthKeyRing{{k2}});
  EXPECT_TRUE(watcher.Poll(3'000'000));
  EXPECT_TRUE(watcher.error().empty());
  EXPECT_EQ(watcher.keys().keys.size(), 1u);
}

}  // namespace
}  // namespace minenav
