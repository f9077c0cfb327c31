#include "progress.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace chaosweep {

namespace {
std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  char buf[32];
  const long t = long(s + 0.5);
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}
}  // namespace

std::string ProgressReporter::line(std::int64_t done, std::int64_t total, std::int64_t failed, double seconds) {
  const double rate = seconds > 0 ? double(done) / seconds : 0.0;
  const double eta = rate > 0 ? double(total - done) / rate : NAN;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%lld/%lld runs (%.1f%%), %.0f runs/s, ETA %s, %lld not ok",
                (long long)done, (long long)total, total ? 100.0 * double(done) / double(total) : 100.0, rate,
                done == total ? "0s" : duration_text(eta).c_str(), (long long)failed);
  return buf;
}

ProgressReporter::ProgressReporter(const ProgressCounters& counters, std::int64_t total, ProgressMode mode,
                                   std::chrono::seconds interval)
    : counters_(counters), total_(total), tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {
  // automatic and always behave alike here; the CLI maps `-q` + auto to never.
  enabled_ = mode != ProgressMode::never;
  period_ = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(interval);
  if (enabled_) thread_ = std::thread([this] { loop(); });
}

ProgressReporter::~ProgressReporter() {
  if (!enabled_) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  print(true);
}

void ProgressReporter::loop() {
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, period_, [this] { return stop_; })) print(false);
}

void ProgressReporter::print(bool final_line) {
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string text = line(counters_.done.load(), total_, counters_.failed.load(), s);
  if (tty_) std::fprintf(stderr, "\r\033[K%s%s", text.c_str(), final_line ? "\n" : "");
  else std::fprintf(stderr, "progress: %s\n", text.c_str());
  std::fflush(stderr);
}

}  // namespace chaosweep
