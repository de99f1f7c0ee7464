#pragma once
// Writing canonical logs atomically: rows go to a temporary file beside the
// target, which replaces the target only on Commit(). Numbers are written in
// the shortest form that reads back to the same double (std::to_chars), so a
// read–write round trip is bit-exact.

#include <string>

#include "pliant/io/atomic_file.h"
#include "pliant/io/log.h"

namespace pliant::io {

class LogWriter {
 public:
  /// Writes metadata and header. Throws std::system_error if the directory is
  /// not writable.
  LogWriter(const std::string& path, const LogHeader& header);

  /// One row of header.columns.size() values in header order.
  void Write(const double* values);
  /// Flushes and renames over the target; without it nothing is left behind.
  void Commit();

 private:
  AtomicFile file_;
  std::size_t columns_;
  std::string line_;
};

void WriteLog(const std::string& path, const Log& log);

}  // namespace pliant::io
