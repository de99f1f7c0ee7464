#pragma once
// Output that is never torn and never destroys what it writes to.
//
// Where the output goes decides how it is written:
//   - a new name or a regular file: replaced atomically, through a temporary
//     in the target's directory renamed over it only when complete. A process
//     killed midway leaves the old file (or none), never half a new one;
//   - a symbolic link: followed; the file it leads to is treated as above, and
//     the link itself stays;
//   - a character device (/dev/null, a terminal) or a FIFO: written through,
//     as a shell redirection would (renaming over them would replace the device
//     node or the pipe with a regular file);
//   - "-": standard output, written through;
//   - anything else (a directory, a block device, a socket): refused with an
//     InputError naming the path, before any work.

#include <cstdio>
#include <string>
#include <string_view>

namespace pliant::io {

/// The path that means standard input (for a reader) or standard output (for a writer).
inline constexpr std::string_view kStandardStream = "-";

class AtomicFile {
 public:
  /// Opens the output (creating the temporary when it is replaced). Throws
  /// InputError when the path names something that cannot take a file's
  /// contents, std::system_error naming the path when it cannot be opened.
  explicit AtomicFile(std::string path);
  /// Removes the temporary file unless Commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void Write(std::string_view bytes);
  /// Flushes; a replaced file is synced and renamed over its target. Throws
  /// std::system_error.
  void Commit();

  const std::string& path() const { return path_; }
  /// True when the bytes go straight to a device, a FIFO or standard output.
  bool writes_through() const { return write_through_; }

 private:
  void OpenTemporary();
  void OpenThrough(const std::string& destination);

  std::string path_;
  std::string target_path_;     ///< the file replaced (a symbolic link's target)
  std::string temporary_path_;
  std::FILE* stream_ = nullptr;
  bool committed_ = false;
  bool anonymous_ = false;  ///< the data is in an unnamed O_TMPFILE file
  bool write_through_ = false;
};

/// Writes a whole file atomically.
void WriteFileAtomically(const std::string& path, std::string_view contents);

}  // namespace pliant::io
