#include "pliant/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "pliant/io/input_error.h"

namespace pliant::io {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void ThrowErrno(const std::string& what) {
  throw std::system_error(errno, std::generic_category(), what);
}

// The temporary must live in the target's directory: rename() is atomic only
// within one file system. pid + counter keep concurrent writers apart.
std::string TemporaryPath(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path target(path);
  const std::string name = "." + target.filename().string() + ".tmp." + std::to_string(::getpid()) +
                           "." + std::to_string(counter++);
  return (target.parent_path() / name).string();
}

std::string DirectoryOf(const std::string& path) {
  const std::string directory = fs::path(path).parent_path().string();
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

// The file a chain of symbolic links ends at (which may not exist yet: a
// dangling link names the file to create). A loop is bad input.
std::string FollowLinks(const std::string& path) {
  fs::path current(path);
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code error;
    if (!fs::is_symlink(fs::symlink_status(current, error))) return current.string();
    const fs::path next = fs::read_symlink(current, error);
    if (error) throw std::system_error(error, "cannot read the link " + current.string());
    current = next.is_absolute() ? next : current.parent_path() / next;
  }
  throw InputError(path, 0, 0, "the output is a loop of symbolic links",
                   "give a regular file, or a link that leads to one");
}

enum class Kind { kReplace, kWriteThrough };

// How a target may be written: replaced when it is a regular file or absent,
// written through when it is a character device or a FIFO, refused otherwise.
Kind KindOf(const std::string& path, const std::string& target) {
  struct stat status {};
  if (::stat(target.c_str(), &status) != 0) {
    if (errno == ENOENT) return Kind::kReplace;
    ThrowErrno("cannot write " + path);
  }
  if (S_ISREG(status.st_mode)) return Kind::kReplace;
  if (S_ISCHR(status.st_mode) || S_ISFIFO(status.st_mode)) return Kind::kWriteThrough;
  const char* what = S_ISDIR(status.st_mode)   ? "a directory"
                     : S_ISBLK(status.st_mode) ? "a block device (a disk: writing would "
                                                 "overwrite its file system)"
                     : S_ISSOCK(status.st_mode) ? "a socket"
                                                : "not a regular file";
  throw InputError(path, 0, 0, std::string("the output is ") + what,
                   "give a file name (a new one, or a regular file to replace), a FIFO, a "
                   "character device such as /dev/null, or - for standard output");
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  if (path_ == kStandardStream) {
    write_through_ = true;
    const int fd = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 0);
    if (fd < 0) ThrowErrno("cannot write to standard output");
    stream_ = ::fdopen(fd, "wb");
    if (stream_ == nullptr) {
      ::close(fd);
      ThrowErrno("cannot write to standard output");
    }
    return;
  }
  target_path_ = FollowLinks(path_);
  if (KindOf(path_, target_path_) == Kind::kWriteThrough) {
    OpenThrough(target_path_);
  } else {
    OpenTemporary();
  }
}

// A device or a FIFO is opened as a shell redirection would open it: no
// creation, no truncation (neither has a length), blocking until a FIFO has a
// reader.
void AtomicFile::OpenThrough(const std::string& destination) {
  write_through_ = true;
  const int fd = ::open(destination.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) ThrowErrno("cannot write " + path_);
  stream_ = ::fdopen(fd, "wb");
  if (stream_ == nullptr) {
    ::close(fd);
    ThrowErrno("cannot write " + path_);
  }
}

// Where the file system allows, the data goes to an unnamed file (O_TMPFILE)
// that is given a name only at Commit(): a process killed before then (even by
// SIGKILL, when no destructor runs) leaves nothing behind. Elsewhere a named
// temporary is used and removed by the destructor.
void AtomicFile::OpenTemporary() {
  temporary_path_ = TemporaryPath(target_path_);
  int fd = ::open(DirectoryOf(target_path_).c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
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
  if (!anonymous_ && !write_through_) std::remove(temporary_path_.c_str());
}

void AtomicFile::Write(std::string_view bytes) {
  if (stream_ == nullptr) throw std::logic_error("AtomicFile::Write after Commit: " + path_);
  if (std::fwrite(bytes.data(), 1, bytes.size(), stream_) != bytes.size()) {
    ThrowErrno("cannot write " + path_);
  }
}

void AtomicFile::Commit() {
  if (stream_ == nullptr) throw std::logic_error("AtomicFile::Commit twice: " + path_);
  if (write_through_) {
    const bool flushed = std::fflush(stream_) == 0;
    const int closed = std::fclose(stream_);
    stream_ = nullptr;
    if (!flushed || closed != 0) ThrowErrno("cannot write " + path_);
    committed_ = true;
    return;
  }
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
  if (std::rename(temporary_path_.c_str(), target_path_.c_str()) != 0) {
    ThrowErrno("cannot replace " + path_);
  }
  committed_ = true;
  SyncDirectory(target_path_);
}

void WriteFileAtomically(const std::string& path, std::string_view contents) {
  AtomicFile file(path);
  file.Write(contents);
  file.Commit();
}

}  // namespace pliant::io
