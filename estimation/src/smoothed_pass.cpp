#include "smoothed_pass.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <stdexcept>

namespace pliant::estimation {

CheckpointedSmoother::CheckpointedSmoother(const models::ModelParameters& parameters,
                                           const FilterOptions& options,
                                           std::size_t block_records)
    : filter_(parameters, options), block_(block_records) {
  if (block_ == 0) throw std::invalid_argument("CheckpointedSmoother: block_records must be ≥ 1");
  checkpoints_.push_back({filter_, 0, 0.0});
}

FilterEstimate CheckpointedSmoother::Add(const FilterSample& sample) {
  const FilterEstimate estimate = filter_.Step(sample);
  ++samples_;
  if (filter_.advanced()) Count();
  return estimate;
}

// The filter's state reached one more sample: its record's depth (as
// RecordStep keeps it), and a checkpoint where a block starts.
void CheckpointedSmoother::Count() {
  const double depth = filter_.state_sample().insertion_depth_m;
  if (std::isfinite(depth) || records_ == 0) last_depth_m_ = depth;
  ++records_;
  if (records_ % block_ != 0) return;
  checkpoints_.push_back({filter_, samples_, last_depth_m_});
  if (checkpoints_.size() * kRecordsPerCheckpoint <= block_ || checkpoints_.size() <= kMinCheckpoints) return;
  // Too many checkpoints for the block: keep every other, blocks twice as long.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < checkpoints_.size(); i += 2) {
    checkpoints_[kept++] = std::move(checkpoints_[i]);
  }
  checkpoints_.erase(checkpoints_.begin() + std::ptrdiff_t(kept), checkpoints_.end());
  block_ *= 2;
  // The newest checkpoint may now sit at an odd multiple of the old block:
  // dropped above, as it should be; the next lands at a multiple of the new.
}

// Block b's records, filtered, rebuilt from its checkpoint: the filter makes
// one record per sample once it holds alignment_steps() samples, and the
// held ones at the log's end.
void CheckpointedSmoother::RecomputeBlock(std::size_t b, const ReadSamples& read,
                                          std::vector<SmootherStep>* steps) {
  const Checkpoint& checkpoint = checkpoints_[b];
  const std::size_t first = b * block_;
  const std::size_t count = std::min(block_, records_ - first);
  ComplianceFilter filter = checkpoint.filter;
  const std::size_t lead = std::size_t(std::max(filter.alignment_steps(), 0));
  read(checkpoint.next_sample, std::min(count + lead, samples_ - checkpoint.next_sample),
       &samples_buffer_);
  steps->clear();
  double depth = checkpoint.last_depth_m;
  const auto record = [&] {
    steps->push_back(RecordStep(filter, depth, first + steps->size() == 0));
    depth = steps->back().depth_m;
  };
  for (const FilterSample& sample : samples_buffer_) {
    if (steps->size() == count) break;
    filter.Step(sample);
    if (filter.advanced()) record();
  }
  while (steps->size() < count && filter.StepHeldSample()) record();
  if (steps->size() != count) throw std::logic_error("CheckpointedSmoother: a block came out short");
}

void CheckpointedSmoother::Smooth(const ReadSamples& read, const TakeBlock& take) {
  while (filter_.StepHeldSample()) Count();  // the log's last samples
  if (records_ == 0) return;
  const std::size_t blocks = (records_ + block_ - 1) / block_;
  SmootherStep next;
  std::vector<FilterEstimate> estimates;
  std::vector<SmootherStep> steps, upcoming;
  RecomputeBlock(blocks - 1, read, &steps);
  for (std::size_t b = blocks; b-- > 0;) {
    // The block before is recomputed on a second thread meanwhile (it needs
    // only its checkpoint): the two halves of the work overlap.
    std::future<void> before;
    if (b > 0) {
      before = std::async(std::launch::async, [&, b] { RecomputeBlock(b - 1, read, &upcoming); });
    }
    if (b + 1 < blocks) SmoothStep(&steps.back(), next);
    for (std::size_t k = steps.size() - 1; k-- > 0;) SmoothStep(&steps[k], steps[k + 1]);
    next = steps.front();
    estimates.resize(steps.size());
    std::transform(steps.begin(), steps.end(), estimates.begin(), StepEstimate);
    take(b * block_, estimates);
    if (b > 0) {
      before.get();
      std::swap(steps, upcoming);
    }
  }
}

}  // namespace pliant::estimation
