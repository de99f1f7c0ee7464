#pragma once
// Where a command prints its summary: standard output, unless its output file
// is standard output itself (-o -), whose bytes must be the log's alone so a
// pipe can read them.
#include <cstdio>
#include <string>

#include "pliant/io/atomic_file.h"

namespace pliant::cli {

inline std::FILE* SummaryStream(const std::string& output_path) {
  return output_path == io::kStandardStream ? stderr : stdout;
}

}  // namespace pliant::cli
