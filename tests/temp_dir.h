#pragma once
// A folder of this test process's own files (PREFIX_<pid>_<n>, a new n for every object),
// removed with everything in it when the object goes out of scope.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace minenav::testing {

class TempDir {
 public:
  explicit TempDir(const std::string& prefix)
      : path_(std::filesystem::temp_directory_path() /
              (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(NextNumber()))) {
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }

 private:
  static int NextNumber() {
    static int next = 0;
    return next++;
  }

  std::filesystem::path path_;
};

// A path in one folder of this test binary's own, removed when the binary exits: for tests
// that need a file or two and no folder of their own.
inline std::string TempPath(const std::string& name) {
  static TempDir dir("minenav_test");
  return dir / name;
}

}  // namespace minenav::testing
