#include "scratch_file.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace pliant::estimation {
namespace {

constexpr std::size_t kBufferDoubles = 1 << 17;  // 1 MiB

[[noreturn]] void Fail(const std::string& what, const std::string& doing) {
  throw std::runtime_error("scratch file (" + what + "): " + doing + ": " +
                           std::strerror(errno) + " — free space in TMPDIR or set TMPDIR");
}

}  // namespace

ScratchFile::ScratchFile(std::string what) : what_(std::move(what)) {
  std::error_code error;
  std::filesystem::path dir = std::filesystem::temp_directory_path(error);
  if (error) dir = "/tmp";
  std::string name = (dir / "pliant-scratch-XXXXXX").string();
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) Fail(what_, "cannot create in " + dir.string());
  ::unlink(name.c_str());  // gone from the directory now; the data lives while fd_ is open
  buffer_.reserve(kBufferDoubles);
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::Append(const double* values, std::size_t count) {
  if (buffer_.size() + count > kBufferDoubles) Flush();
  if (count > kBufferDoubles) {
    Write(appended_, values, count);
    appended_ += count;
    return;
  }
  buffer_.insert(buffer_.end(), values, values + count);
}

void ScratchFile::Flush() {
  if (buffer_.empty()) return;
  Write(appended_, buffer_.data(), buffer_.size());
  appended_ += buffer_.size();
  buffer_.clear();
}

void ScratchFile::Write(std::size_t offset, const double* values, std::size_t count) {
  const char* data = reinterpret_cast<const char*>(values);
  std::size_t bytes = count * sizeof(double);
  off_t at = off_t(offset * sizeof(double));
  while (bytes > 0) {
    const ssize_t n = ::pwrite(fd_, data, bytes, at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail(what_, "cannot write");
    data += n, at += n, bytes -= std::size_t(n);
  }
}

void ScratchFile::Read(std::size_t offset, std::size_t count, double* values) {
  Flush();
  char* data = reinterpret_cast<char*>(values);
  std::size_t bytes = count * sizeof(double);
  off_t at = off_t(offset * sizeof(double));
  while (bytes > 0) {
    const ssize_t n = ::pread(fd_, data, bytes, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) Fail(what_, "cannot read");
    if (n == 0) {
      errno = 0;
      throw std::runtime_error("scratch file (" + what_ + "): read past its end");
    }
    data += n, at += n, bytes -= std::size_t(n);
  }
}

}  // namespace pliant::estimation
