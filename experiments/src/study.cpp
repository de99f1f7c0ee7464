// Trial streams and draws (study.h): counter-based, so trial k's numbers are
// the same on any thread or rank.
#include <algorithm>
#include <cmath>

#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/uniform.hpp>

#include "pliant/experiments/study.h"

namespace pliant::experiments {
namespace {

constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ull;

std::uint64_t Mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

const char* SampledQuantityName(int quantity) {
  static const char* const kNames[kSampledQuantities] = {
      "compliance_scale1", "compliance_scale2", "backlash1_rad",  "backlash2_rad",
      "bias_offset1_nm",   "bias_offset2_nm",   "effort_sd_nm",   "depth_m",
      "direction_deg",     "peak_torque_nm",    "speed_rad_s",    "shaft_start1",
      "shaft_start2"};
  return kNames[quantity];
}

double Distribution::Quantile(double u) const {
  double x = a;
  switch (kind) {
    case Kind::kConstant:
      break;
    case Kind::kUniform:
      x = b > a ? boost::math::quantile(boost::math::uniform(a, b), u) : a;
      break;
    case Kind::kNormal:
      x = b > 0.0 ? boost::math::quantile(boost::math::normal(a, b), u) : a;
      break;
    case Kind::kLogNormal:
      x = b > 0.0 ? boost::math::quantile(boost::math::lognormal(std::log(a), b), u) : a;
      break;
  }
  return std::clamp(x, lower, upper);
}

TrialStream::TrialStream(std::uint64_t study_seed, std::uint64_t trial)
    : state_(Mix(Mix(study_seed) + trial * kGolden)) {}

std::uint64_t TrialStream::Next() { return Mix(state_ += kGolden); }

double TrialStream::Uniform() {
  return static_cast<double>(Next() >> 11) * 0x1.0p-53 + 0x1.0p-54;
}

TrialDraw DrawTrial(const Study& study, TrialStream& stream) {
  TrialDraw draw;
  for (int q = 0; q < kShaftStart1; ++q) draw.values[q] = study.quantities[q].Quantile(stream.Uniform());
  draw.simulation_seed = stream.Next();
  draw.nees_pick = stream.Uniform();
  for (int q = kShaftStart1; q < kSampledQuantities; ++q) {
    const Distribution& d = study.quantities[q];
    draw.values[q] = d.kind == Distribution::Kind::kConstant ? d.a : d.Quantile(stream.Uniform());
  }
  return draw;
}

}  // namespace pliant::experiments
