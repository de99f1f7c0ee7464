#include "pliant/estimation/identification_data.h"

#include <cmath>

#include "pliant/models/travel_since_reversal.h"

namespace pliant::estimation {

bool SampleExtractionOptions::IsValid(std::string* error) const {
  if (!(hold_tolerance_rad > 0.0)) {
    *error = "hold_tolerance_rad must be > 0";
    return false;
  }
  if (!(rest_velocity_rad_s > 0.0)) {
    *error = "rest_velocity_rad_s must be > 0";
    return false;
  }
  return true;
}

std::size_t IdentificationData::CountTipFixed() const {
  std::size_t n = 0;
  for (const auto& s : samples) n += s.tip_fixed;
  return n;
}

namespace {

// Running sums of one hold.
struct Hold {
  IdentificationSample sum;
  Eigen::Vector2d first_angle_rad;
  double first_depth_m = 0.0;
  int rows = 0;

  void Add(const IdentificationSample& s) {
    if (rows == 0) {
      sum = s;
      first_angle_rad = s.angle_rad;
      first_depth_m = s.insertion_depth_m;
    } else {
      sum.angle_rad += s.angle_rad;
      sum.insertion_depth_m += s.insertion_depth_m;
      sum.effort_nm += s.effort_nm;
      sum.travel_since_reversal_rad += s.travel_since_reversal_rad;
    }
    ++rows;
  }
  IdentificationSample Mean() const {
    IdentificationSample mean = sum;
    mean.angle_rad /= rows;
    mean.insertion_depth_m /= rows;
    mean.effort_nm /= rows;
    mean.travel_since_reversal_rad /= rows;
    mean.rows = rows;
    return mean;
  }
};

// A joint the log does not record (NaN) neither moves nor holds still.
bool MovedBeyond(const Eigen::Vector2d& angle, const Eigen::Vector2d& first, double tolerance) {
  for (int j = 0; j < 2; ++j) {
    if (std::abs(angle[j] - first[j]) > tolerance) return true;
  }
  return false;
}

}  // namespace

void AppendSamples(const io::Log& log, const std::string& name,
                   const SampleExtractionOptions& options, IdentificationData* data) {
  const io::StandardColumns c(log.header);
  data->logs.push_back(name);
  Hold hold;
  auto flush = [&] {
    if (hold.rows > 0) data->samples.push_back(hold.Mean());
    hold.rows = 0;
  };
  models::TravelSinceReversal travel;
  bool first = true;
  double last_segment = 0.0, last_fixed = 0.0;
  for (std::size_t r = 0; r < log.Rows(); ++r) {
    ++data->log_rows;
    const double segment = c.segment >= 0 ? log.Value(r, c.segment) : 0.0;
    const double fixed = c.tip_fixed >= 0 ? log.Value(r, c.tip_fixed) : 0.0;
    if (first || segment != last_segment || fixed != last_fixed) {
      flush();
      data->segments += 1;
      first = false;
      last_segment = segment;
      last_fixed = fixed;
    }
    if (c.v1 >= 0 && c.v2 >= 0) {
      const double v1 = log.Value(r, c.v1), v2 = log.Value(r, c.v2);
      // A missing velocity (NaN) says nothing: keep the row.
      if (std::abs(v1) > options.rest_velocity_rad_s || std::abs(v2) > options.rest_velocity_rad_s) {
        ++data->moving_rows;
        flush();
        continue;
      }
    }
    IdentificationSample s;
    s.angle_rad << log.Value(r, c.q1), log.Value(r, c.q2);
    s.insertion_depth_m = log.Value(r, c.q3);
    s.effort_nm << log.Value(r, c.tau1), log.Value(r, c.tau2);
    s.travel_since_reversal_rad = travel.Update(s.angle_rad);
    s.tip_fixed = fixed > 0.5;
    s.segment = data->segments - 1;
    s.log = int(data->logs.size()) - 1;
    if (hold.rows > 0 && (!options.average_holds ||
                          MovedBeyond(s.angle_rad, hold.first_angle_rad,
                                      options.hold_tolerance_rad) ||
                          std::abs(s.insertion_depth_m - hold.first_depth_m) > 1e-4)) {
      flush();
    }
    hold.Add(s);
  }
  flush();
}

}  // namespace pliant::estimation
