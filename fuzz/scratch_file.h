#pragma once
// A fuzz input as a file, for the parsers that read a path (LogReader, ReadCarmenLog): an
// anonymous in-memory file (memfd_create) opened through /proc/self/fd, so that millions of
// inputs touch no disk and leave nothing behind.

#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <string>

namespace minenav::fuzz {

class ScratchFile {
 public:
  ScratchFile(const uint8_t* data, size_t size) : fd_(memfd_create("minenav_fuzz", 0)) {
    if (fd_ < 0) std::abort();
    size_t done = 0;
    while (done < size) {
      const ssize_t n = write(fd_, data + done, size - done);
      if (n <= 0) std::abort();
      done += static_cast<size_t>(n);
    }
  }
  ~ScratchFile() { close(fd_); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  std::string path() const { return "/proc/self/fd/" + std::to_string(fd_); }

 private:
  int fd_;
};

}  // namespace minenav::fuzz
