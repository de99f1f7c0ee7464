// A temporary binary file of doubles, for the data a pass must read again
// (the smoothed pass's input rows and its smoothed values). Created in TMPDIR
// (else /tmp) and unlinked at once: the system removes it when the object
// closes it or the process ends, however it ends. Failures throw
// std::runtime_error (a runtime failure, exit 1).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pliant::estimation {

class ScratchFile {
 public:
  /// `what` names the file's use in error messages.
  explicit ScratchFile(std::string what);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  /// Appends `count` doubles after the last appended (buffered).
  void Append(const double* values, std::size_t count);
  /// Writes `count` doubles at double offset `offset`.
  void Write(std::size_t offset, const double* values, std::size_t count);
  /// Reads `count` doubles from double offset `offset` (all must exist).
  void Read(std::size_t offset, std::size_t count, double* values);

 private:
  void Flush();

  std::string what_;
  int fd_ = -1;
  std::size_t appended_ = 0;   // doubles appended and flushed
  std::vector<double> buffer_;  // appended, not yet written
};

}  // namespace pliant::estimation
