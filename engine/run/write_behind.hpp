#pragma once
// Runs a sweep's writes on a thread of their own, one at a time and in the
// order handed over, so that batch b's rows are written while batch b + 1
// runs: the write (HDF5, one thread) left the sweep's threads idle.
// At most one write waits behind the running one (a hand-over waits until
// the one handed over before it has started), which bounds the rows held in
// memory to about two batches. A write that throws stops the writes after
// it; its exception is rethrown by the next hand_over or by wait.
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace chaosweep {

class WriteBehind {
 public:
  WriteBehind() = default;
  ~WriteBehind();  // waits for the writes handed over; their failure is lost: call wait() first
  WriteBehind(const WriteBehind&) = delete;
  WriteBehind& operator=(const WriteBehind&) = delete;

  // Queues `write` (empty: nothing to write) behind those handed over
  // before; rethrows an earlier write's failure instead.
  void hand_over(std::function<void()> write);
  // Returns once every write handed over has finished; rethrows the first
  // failure.
  void wait();

 private:
  void loop();
  std::mutex m_;
  std::condition_variable cv_;
  std::optional<std::function<void()>> queued_;  // handed over, not started
  bool writing_ = false, closing_ = false;
  std::exception_ptr failed_;
  std::thread thread_;  // started by the first hand-over
};

}  // namespace chaosweep
