// libFuzzer target: any bytes given to the JHU 2017 importers (clamped beam and
// bias sweep) end in a log that honours the contract — one joint recorded,
// quasi-static, t increasing, q3 in 0-0.3 m, a whole segment number — or in an
// InputError; never a crash, a hang or another exception.
#include <cmath>
#include <cstdlib>

#include "fuzz_input.h"
#include "pliant/io/import.h"
#include "pliant/io/input_error.h"

namespace {

void CheckLog(const pliant::io::Log& log) {
  if (!log.header.QuasiStatic() || log.header.Has("q2") || log.header.Has("tau2")) std::abort();
  const int t = log.header.Index("t"), q3 = log.header.Index("q3");
  const int segment = log.header.Index("segment");
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    if (r > 0 && !(log.Value(r, t) > log.Value(r - 1, t))) std::abort();
    if (!(log.Value(r, q3) >= 0.0 && log.Value(r, q3) <= 0.3)) std::abort();
    const double s = log.Value(r, segment);
    if (!(s >= 0.0 && std::floor(s) == s)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pliant::fuzz::MemoryFile file;
  const std::string& path = file.Hold(data, size);
  try {
    pliant::io::DetectImportFormat(path);
  } catch (const pliant::io::InputError&) {
  }
  for (bool clamped : {true, false}) {
    try {
      CheckLog(clamped ? pliant::io::ImportJhu2017ClampedBeam(path, {1, ""})
                       : pliant::io::ImportJhu2017BiasSweep(path, {1, ""}));
    } catch (const pliant::io::InputError&) {
    }
  }
  return 0;
}
