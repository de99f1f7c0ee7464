#pragma once
// Taring the bias torque on a log's own unloaded rows. The bias drifts from
// one day to the next (docs/real-data.md), so a user's log may disagree with
// the parameters' tau0 by a constant: on rows where nothing touches the
// instrument, the load the model reads (tau − tau0 − internal effects) is
// that constant plus noise.
//
// Found from the data: the longest run of consecutive rows whose load stays
// inside a band of ±band_nm (the load is constant there: no contact, or a
// contact that does not change, which the caller rules out by naming rows
// when it knows them). Any consumer (pliant correct, the filter) calls these
// on the loads it computes with the parameters' bias.

#include <cstddef>
#include <vector>

namespace pliant::estimation {

struct UnloadedRun {
  std::size_t first_row = 0;  ///< index of the first unloaded row
  std::size_t rows = 0;       ///< 0 when no run is long enough
};

/// The longest run of consecutive finite loads (N·m) whose max − min is at
/// most 2·band_nm, if it has at least min_rows rows.
UnloadedRun FindUnloadedRun(const std::vector<double>& load_nm, double band_nm,
                            std::size_t min_rows);

struct TareOffset {
  double offset_nm = 0.0;  ///< mean load over the unloaded rows: add it to tau0
  /// Its standard deviation: sample sd / √n, raised to the batch-means
  /// estimate when consecutive rows share their errors.
  double sd_nm = 0.0;
  std::size_t rows = 0;
  /// The offset exceeds 2·√(sd² + bias_sd²): the log's unloaded rows disagree
  /// with the parameters' bias beyond its σ.
  bool disagrees = false;
};

/// The tare over rows [first, first + rows); `bias_sd_nm` is the parameters'
/// σ of tau0 (0 when they carry none).
TareOffset TareOn(const std::vector<double>& load_nm, UnloadedRun run, double bias_sd_nm);

}  // namespace pliant::estimation
