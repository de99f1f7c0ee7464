#pragma once
// Output that is never torn: a temporary file in the target's directory,
// renamed over the target only when complete. A process killed midway leaves
// the old file (or none), never half a new one.

#include <cstdio>
#include <string>
#include <string_view>

namespace pliant::io {

class AtomicFile {
 public:
  /// Creates the temporary file. Throws std::system_error naming the path.
  explicit AtomicFile(std::string path);
  /// Removes the temporary file unless Commit() succeeded.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void Write(std::string_view bytes);
  /// Flushes, syncs and renames over the target. Throws std::system_error.
  void Commit();

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string temporary_path_;
  std::FILE* stream_ = nullptr;
  bool committed_ = false;
  bool anonymous_ = false;  ///< the data is in an unnamed O_TMPFILE file
};

/// Writes a whole file atomically.
void WriteFileAtomically(const std::string& path, std::string_view contents);

}  // namespace pliant::io
