// libFuzzer target: any bytes given to the log reader end in rows that honour
// the contract (a recorded joint finite, an unrecorded one NaN) or in an InputError — never a crash, a hang, another exception,
// or a row that breaks the contract.
#include <cmath>
#include <cstdlib>

#include "fuzz_input.h"
#include "pliant/io/log_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pliant::fuzz::MemoryFile file;
  const std::string& path = file.Hold(data, size);
  // The last input byte picks the chunk size, so that lines cross chunk
  // boundaries everywhere; skip_bad_rows both off and on.
  const std::size_t chunk = size > 0 ? 2 + data[size - 1] % 64 : 2;
  for (bool skip : {false, true}) {
    try {
      pliant::io::LogReader reader(path, {skip, chunk});
      const pliant::io::StandardColumns c(reader.header());
      double last_t = -INFINITY;
      while (const double* row = reader.Next()) {
        for (int required : {c.t, c.q3}) {
          if (!std::isfinite(row[required])) std::abort();
        }
        // A joint the log does not record reads NaN in every row; a recorded
        // joint is finite in every row.
        for (int joint : {1, 2}) {
          const bool recorded = reader.header().JointRecorded(joint);
          for (int column : {joint == 1 ? c.q1 : c.q2, joint == 1 ? c.tau1 : c.tau2}) {
            if (std::isfinite(row[column]) != recorded) std::abort();
          }
        }
        if (!(row[c.t] > last_t)) std::abort();
        if (!(row[c.q3] >= 0.0 && row[c.q3] <= 0.3)) std::abort();
        last_t = row[c.t];
      }
    } catch (const pliant::io::InputError&) {
    }
  }
  return 0;
}
