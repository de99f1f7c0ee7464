#include "pliant/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

namespace pliant::io {
namespace {

[[noreturn]] void ThrowErrno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

// The temporary must live in the target's directory: rename() is atomic only
// within one file system. pid + counter keep concurrent writers apart.
std::string TemporaryPath(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path target(path);
  const std::string name = "." + target.filename().string() + ".tmp." + std::to_string(::getpid()) +
                           "." + std::to_string(counter++);
  return (target.parent_path() / name).string();
}

std::string DirectoryOf(const std::string& path) {
  const std::string directory = std::filesystem::path(path).parent_path().string();
  return directory.empty() ? "." : directory;
}

// Makes the rename itself durable; best effort, as some file systems refuse it.
void SyncDirectory(const std::string& path) {
  const std::string directory = DirectoryOf(path);
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

}  // namespace

// Where the file system allows, the data goes to an unnamed file (O_TMPFILE)
// that is given a name only at Commit(): a process killed before then (even by
// SIGKILL, when no destructor runs) leaves nothing behind. Elsewhere a named
// temporary is used and removed by the destructor.
AtomicFile::AtomicFile(std::string path)
    : path_(std::move(path)), temporary_path_(TemporaryPath(path_)) {
  int fd = ::open(DirectoryOf(path_).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  anonymous_ = fd >= 0;
  if (!anonymous_) {
    fd = ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  }
  if (fd < 0) ThrowErrno("cannot create a temporary file to write " + path_);
  stream_ = ::fdopen(fd, "wb");
  if (stream_ == nullptr) {
    ::close(fd);
    ThrowErrno("cannot write " + path_);
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  if (stream_ != nullptr) std::fclose(stream_);
  if (!anonymous_) std::remove(temporary_path_.c_str());
}

void AtomicFile::Write(std::string_view bytes) {
  if (stream_ == nullptr) throw std::logic_error("AtomicFile::Write after Commit: " + path_);
  if (std::fwrite(bytes.data(), 1, bytes.size(), stream_) != bytes.size()) {
    ThrowErrno("cannot write " + path_);
  }
}

void AtomicFile::Commit() {
  if (stream_ == nullptr) throw std::logic_error("AtomicFile::Commit twice: " + path_);
  // Data must be on disk before the rename publishes it, or a crash could
  // leave the new name pointing at an empty file.
  if (std::fflush(stream_) != 0 || ::fsync(::fileno(stream_)) != 0) {
    ThrowErrno("cannot write " + path_);
  }
  if (anonymous_) {
    const std::string fd_path = "/proc/self/fd/" + std::to_string(::fileno(stream_));
    if (::linkat(AT_FDCWD, fd_path.c_str(), AT_FDCWD, temporary_path_.c_str(),
                 AT_SYMLINK_FOLLOW) != 0) {
      ThrowErrno("cannot write " + path_);
    }
    anonymous_ = false;  // from here on the temporary has a name to remove
  }
  const int closed = std::fclose(stream_);
  stream_ = nullptr;
  if (closed != 0) ThrowErrno("cannot write " + path_);
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
    ThrowErrno("cannot replace " + path_);
  }
  committed_ = true;
  SyncDirectory(path_);
}

void WriteFileAtomically(const std::string& path, std::string_view contents) {
  AtomicFile file(path);
  file.Write(contents);
  file.Commit();
}

}  // namespace pliant::io
