#pragma once
// Per-map setup that the runs of a sweep share (MapZoning's zones, the cells
// clear of Eq. 8), built once per distinct key instead of once per run: a
// 200 m SR 1 map took 1.1-1.5 ms of setup per run (issue 20). An entry is
// an immutable object, a pure function of its key, so which thread built it
// and in what order the runs came never shows in a result.
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep {

// The exact bytes of everything a setup depends on: two keys are equal only
// when every number is bit for bit the same (the map's size and every
// obstacle, not its name), so two maps never share an entry.
class SetupKey {
 public:
  SetupKey& add(double v) { return append(&v, sizeof v); }
  SetupKey& add(int v) { return append(&v, sizeof v); }
  SetupKey& add(const Environment& env) {
    add(env.lx).add(env.ly).add(int(env.obstacles.size()));
    return append(env.obstacles.data(), env.obstacles.size() * sizeof(Rect));
  }
  const std::string& bytes() const { return bytes_; }

 private:
  SetupKey& append(const void* p, std::size_t n) {
    bytes_.append(static_cast<const char*>(p), n);
    return *this;
  }
  std::string bytes_;
};

// A thread-safe cache of setups of type T, bounded by a total cost (the
// caller's measure of an entry's size, e.g. its cells): the least recently
// used entries go first, and an entry costing more than the bound alone is
// built for its caller but not kept.
template <class T>
class SetupCache {
 public:
  explicit SetupCache(std::size_t max_cost) : max_cost_(max_cost) {}

  // The entry for `key`, made by make() (returning std::shared_ptr<const T>)
  // when missing. make() runs outside the lock, so a slow build blocks no
  // other lookup; when two threads build the same key, both get the first
  // stored (equal by construction).
  template <class Make>
  std::shared_ptr<const T> get(const SetupKey& key, std::size_t cost, Make&& make) {
    {
      const std::lock_guard lock(mutex_);
      if (Entry* e = find(key.bytes())) return touch(*e);
    }
    std::shared_ptr<const T> value = make();
    if (cost > max_cost_) return value;
    const std::lock_guard lock(mutex_);
    if (Entry* e = find(key.bytes())) return touch(*e);
    while (!entries_.empty() && cost_ + cost > max_cost_) evict_oldest();
    entries_.push_back({key.bytes(), value, cost, ++clock_});
    cost_ += cost;
    ++builds_;
    return value;
  }

  // For tests: entries held, and entries ever stored.
  std::size_t size() const {
    const std::lock_guard lock(mutex_);
    return entries_.size();
  }
  std::size_t builds() const {
    const std::lock_guard lock(mutex_);
    return builds_;
  }

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const T> value;
    std::size_t cost;
    std::uint64_t used;
  };

  Entry* find(const std::string& key) {
    for (Entry& e : entries_)
      if (e.key == key) return &e;
    return nullptr;
  }
  std::shared_ptr<const T> touch(Entry& e) {
    e.used = ++clock_;
    return e.value;
  }
  void evict_oldest() {
    std::size_t oldest = 0;
    for (std::size_t k = 1; k < entries_.size(); ++k)
      if (entries_[k].used < entries_[oldest].used) oldest = k;
    cost_ -= entries_[oldest].cost;
    entries_.erase(entries_.begin() + std::ptrdiff_t(oldest));
  }

  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
  std::size_t max_cost_, cost_ = 0, builds_ = 0;
  std::uint64_t clock_ = 0;
};

}  // namespace chaosweep
