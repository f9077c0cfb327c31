#include "engine/run/write_behind.hpp"

namespace chaosweep {

WriteBehind::~WriteBehind() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    closing_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void WriteBehind::hand_over(std::function<void()> write) {
  if (!write) return;
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait(lock, [&] { return !queued_ || failed_; });
  if (failed_) std::rethrow_exception(failed_);
  queued_ = std::move(write);
  if (!thread_.joinable()) thread_ = std::thread([this] { loop(); });
  lock.unlock();
  cv_.notify_all();
}

void WriteBehind::wait() {
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait(lock, [&] { return (!queued_ && !writing_) || failed_; });
  if (failed_) std::rethrow_exception(failed_);
}

void WriteBehind::loop() {
  std::unique_lock<std::mutex> lock(m_);
  for (;;) {
    cv_.wait(lock, [&] { return queued_ || closing_; });
    if (!queued_) return;  // closing, nothing left
    std::function<void()> write = std::move(*queued_);
    queued_.reset();
    writing_ = true;
    lock.unlock();
    cv_.notify_all();  // room for the next hand-over
    std::exception_ptr failure;
    try {
      write();
    } catch (...) {
      failure = std::current_exception();
    }
    write = nullptr;  // what it held goes before the next one is waited for
    lock.lock();
    writing_ = false;
    if (failure && !failed_) failed_ = failure;
    if (failed_) queued_.reset();  // the writes after a failed one are not made
    cv_.notify_all();
  }
}

}  // namespace chaosweep
