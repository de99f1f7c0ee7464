// The RTS smoother in bounded memory (`pliant filter --smooth`): the same
// records and backward steps as FilterSmoother (filter_smoother.h), to the
// bit, without keeping a record per sample. Forward, Add() runs the filter
// and keeps a copy of it (a checkpoint) every block of B records; Smooth()
// then walks the blocks from the last: restores the block's checkpoint,
// re-runs the filter over the block's samples (read again through the
// caller's ReadSamples) to rebuild its records, and smooths them from the
// next block's first smoothed record.
//
// Memory: the checkpoints and one block of records. When the checkpoints
// outnumber max(kMinCheckpoints, B / kRecordsPerCheckpoint), every other one
// is dropped and B doubles, so both parts stay alike and grow as √N (N
// samples): 10⁷ samples, blocks of 16,384 and 610 checkpoints, about 40 MB.
// Time: the filter runs twice over every sample, plus the backward steps;
// the recomputation of a block runs on a second thread while the block after
// it is smoothed (two blocks of records in memory then).
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "pliant/estimation/filter.h"
#include "pliant/estimation/filter_smoother.h"

namespace pliant::estimation {

class CheckpointedSmoother {
 public:
  /// Fills `samples` with `count` samples from sample `first` on (the ones
  /// given to Add, in order). Called on a second thread, while TakeBlock
  /// runs: the two must share no unguarded state.
  using ReadSamples =
      std::function<void(std::size_t first, std::size_t count, std::vector<FilterSample>* samples)>;
  /// Receives the smoothed estimates of samples first, first + 1, … (one
  /// block; the blocks arrive from the log's end to its start).
  using TakeBlock = std::function<void(std::size_t first, const std::vector<FilterEstimate>&)>;

  /// A checkpoint (a filter copy, about 29 kB) weighs as much as about 23
  /// records with their estimates (1.26 kB each); thinned at 16, the two
  /// parts stay within a factor 3 of each other.
  static constexpr std::size_t kRecordsPerCheckpoint = 16;
  /// Never thinned below this many checkpoints.
  static constexpr std::size_t kMinCheckpoints = 64;

  /// Throws as ComplianceFilter's constructor does. `block_records` is the
  /// first B (≥ 1).
  CheckpointedSmoother(const models::ModelParameters& parameters, const FilterOptions& options,
                       std::size_t block_records = 1024);

  /// Filters one sample; returns the filter's estimate.
  FilterEstimate Add(const FilterSample& sample);

  /// The backward pass; call once, after the last Add.
  void Smooth(const ReadSamples& read, const TakeBlock& take);

  std::size_t block_records() const { return block_; }
  std::size_t checkpoints() const { return checkpoints_.size(); }

 private:
  struct Checkpoint {
    ComplianceFilter filter;  // as it was after the step that made the block's first record − 1
    std::size_t next_sample;  // the sample it takes next
    double last_depth_m;      // the previous record's depth
  };

  void Count();
  void RecomputeBlock(std::size_t block, const ReadSamples& read, std::vector<SmootherStep>* steps);

  ComplianceFilter filter_;
  std::size_t block_;
  std::size_t samples_ = 0, records_ = 0;
  double last_depth_m_ = 0.0;
  std::vector<Checkpoint> checkpoints_;
  std::vector<FilterSample> samples_buffer_;
};

}  // namespace pliant::estimation
