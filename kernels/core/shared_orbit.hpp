#pragma once
// Where a run's draws from a chaotic map's orbit come from: its first few it
// computes itself, the later ones from blocks that the runs of a sweep share
// (SetupCache). Runs that start a map with the same parameters from the
// same state draw the same values, and the C library's trigonometry in a
// planner's map was up to a quarter of its time (issue 20). A block is a
// pure function of the orbit's key and its index, so sharing never shows in
// a result. A block is built when a second run reaches it (the first leaves
// a mark and draws on): an orbit that no other run draws costs a mark per
// block, never values that no one reads.
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "kernels/core/setup_cache.hpp"

namespace chaosweep {

// Value: what a run draws at each iterate, with the iterate as its member x.
template <class Value>
struct OrbitBlock {
  std::vector<Value> values;  // empty: a mark (one run has reached the block)
};

template <class Value>
class SharedOrbit {
 public:
  using Block = OrbitBlock<Value>;
  using Cache = SetupCache<Block>;

  // Draws the run computes itself before the first block.
  static constexpr long own_draws = 32;

  // The orbit from x0; `key` says what makes two orbits the same (the map's
  // parameters and x0, bit for bit).
  SharedOrbit(SetupKey key, double x0, Cache& cache) : key_(std::move(key)), cache_(&cache), x_(x0) {}

  // The next value from a shared block, or null: the run draws this one
  // itself, from state() (the last iterate it drew, or a block's last).
  // fill(x): the value after iterate x, and x becomes its iterate; a block
  // is n calls of it from the iterate before the block.
  template <class Fill>
  const Value* take(Fill&& fill) {
    return at_ != end_ ? at_++ : next_block(fill);
  }
  double& state() { return x_; }
  // Up to n values at once, [first, last), from the block being read: what
  // n calls of take() would give while the block lasts (empty: the next
  // value is the run's own or a new block's, take() it). A caller that
  // stops early gives the values it did not read back (give_back).
  void take_span(long n, const Value*& first, const Value*& last) {
    first = at_;
    at_ += std::min(n, long(end_ - at_));
    last = at_;
  }
  void give_back(long n) { at_ -= n; }

 private:
  // Block j holds 64 * 2^j values (at most 2^16) after the span before it
  // (the run's own, then blocks 0 .. j - 1): a run that stops early draws
  // little it does not use, one that runs long looks the cache up seldom.
  static long block_size(int j) { return long(64) << std::min(j, 10); }

  template <class Fill>
  const Value* next_block(Fill& fill) {
    if (block_) {  // a block read to its end: the run goes on from its last
      x_ = block_->values.back().x;
      block_.reset();
      at_ = end_ = nullptr;
    }
    if (drawn_ < own_end_) return ++drawn_, nullptr;
    const int j = ++index_;
    const long n = block_size(j);
    SetupKey key = key_;
    key.add(j);
    bool first = false;
    static const auto mark = std::make_shared<const Block>();
    std::shared_ptr<const Block> b = cache_->get(key, 1, [&] {
      first = true;
      return mark;
    });
    if (first) {  // no run has drawn this far: draw on, leaving the mark
      own_end_ = drawn_ + n;
      return ++drawn_, nullptr;
    }
    if (b->values.empty()) {  // a second run: the orbit is shared, build
      auto built = std::make_shared<Block>();
      built->values.resize(std::size_t(n));
      double x = x_;
      for (Value& v : built->values) v = fill(x);
      cache_->replace(key, std::size_t(n), built);
      b = std::move(built);
    }
    block_ = std::move(b);
    drawn_ += n;
    own_end_ = drawn_;
    at_ = block_->values.data();
    end_ = at_ + block_->values.size();
    return at_++;
  }

  SetupKey key_;
  Cache* cache_;
  double x_;                  // the last iterate the run drew itself
  long drawn_ = 0;            // values drawn (a block's all at once, when taken)
  long own_end_ = own_draws;  // the run draws its own values up to here
  int index_ = -1;            // the last block looked up
  std::shared_ptr<const Block> block_;
  const Value* at_ = nullptr;
  const Value* end_ = nullptr;
};

}  // namespace chaosweep
