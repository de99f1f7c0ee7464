#pragma once
// Fuzz input as a file the readers can open by path, without touching the disk:
// an anonymous memory file (memfd) reached through /proc/self/fd.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace pliant::fuzz {

class MemoryFile {
 public:
  MemoryFile() : fd_(memfd_create("pliant_fuzz", 0)) {
    if (fd_ < 0) std::abort();
    path_ = "/proc/self/fd/" + std::to_string(fd_);
  }
  ~MemoryFile() { ::close(fd_); }

  /// Replaces the file's contents with `data`.
  const std::string& Hold(const std::uint8_t* data, std::size_t size) {
    if (ftruncate(fd_, 0) != 0 || pwrite(fd_, data, size, 0) != static_cast<ssize_t>(size)) {
      std::abort();
    }
    return path_;
  }

 private:
  int fd_;
  std::string path_;
};

}  // namespace pliant::fuzz
