#pragma once
// Setup that the runs of a sweep share (per map MapZoning's zones and the
// cells clear of Eq. 8; the chaotic maps' orbits, SharedOrbit), built once
// per distinct key instead of once per run: a 200 m SR 1 map took 1.1-1.5
// ms of setup per run (issue 20). An entry is an immutable object, a pure
// function of its key, so which thread built it and in what order the runs
// came never shows in a result.
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

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
      if (auto hit = use(key.bytes())) return hit;
    }
    std::shared_ptr<const T> value = make();
    if (cost > max_cost_) return value;
    const std::lock_guard lock(mutex_);
    if (auto hit = use(key.bytes())) return hit;
    insert(key, cost, value);
    return value;
  }

  // Stores `value` for `key` in place of the entry it has (a placeholder
  // that get() stored), or as a new one.
  void replace(const SetupKey& key, std::size_t cost, std::shared_ptr<const T> value) {
    const std::lock_guard lock(mutex_);
    if (const auto it = index_.find(key.bytes()); it != index_.end()) {
      const auto entry = it->second;
      cost_ -= entry->cost;
      index_.erase(it);  // before the key it views
      entries_.erase(entry);
    }
    if (cost <= max_cost_) insert(key, cost, std::move(value));
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
  };

  // Most recently used first, found by key in constant time: an orbit's
  // blocks and marks are thousands of entries, and a sweep whose orbits
  // never repeat evicts one for every mark it adds.
  std::shared_ptr<const T> use(const std::string& key) {  // null: none
    const auto it = index_.find(key);
    if (it == index_.end()) return nullptr;
    entries_.splice(entries_.begin(), entries_, it->second);
    return it->second->value;
  }
  void insert(const SetupKey& key, std::size_t cost, std::shared_ptr<const T> value) {
    while (!entries_.empty() && cost_ + cost > max_cost_) evict_oldest();
    entries_.push_front({key.bytes(), std::move(value), cost});
    index_.emplace(entries_.front().key, entries_.begin());
    cost_ += cost;
    ++builds_;
  }
  void evict_oldest() {
    cost_ -= entries_.back().cost;
    index_.erase(entries_.back().key);
    entries_.pop_back();
  }

  mutable std::mutex mutex_;
  std::list<Entry> entries_;
  std::unordered_map<std::string_view, typename std::list<Entry>::iterator> index_;  // views of entries_' keys
  std::size_t max_cost_, cost_ = 0, builds_ = 0;
};

}  // namespace chaosweep
