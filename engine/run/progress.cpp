#include "engine/run/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace chaosweep {

std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  char buf[32];
  const long t = long(s + 0.5);
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", t / 3600, (t / 60) % 60);
  else if (t >= 60) std::snprintf(buf, sizeof buf, "%ldm%02lds", t / 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%lds", t);
  return buf;
}

int terminal_width(int fd) {
  winsize ws{};
  if (ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  if (const char* c = std::getenv("COLUMNS")) {
    const int n = std::atoi(c);
    if (n > 0) return n;
  }
  return 80;
}

std::string ProgressReporter::line(std::int64_t done, std::int64_t total, std::int64_t failed, double seconds,
                                   int width) {
  const double rate = seconds > 0 ? double(done) / seconds : 0.0;
  const double eta = rate > 0 ? double(total - done) / rate : NAN;
  const double pct = total ? 100.0 * double(done) / double(total) : 100.0;
  const std::string eta_text = done == total ? "0s" : duration_text(eta);
  const auto d = (long long)done, n = (long long)total, f = (long long)failed;
  char buf[4][160];
  // From the full line to the least that still says where the sweep is.
  std::snprintf(buf[0], sizeof buf[0], "%lld/%lld runs (%.1f%%), %.0f runs/s, ETA %s, %lld not ok", d, n, pct, rate,
                eta_text.c_str(), f);
  std::snprintf(buf[1], sizeof buf[1], "%lld/%lld %.1f%% %.0f/s ETA %s %lld not ok", d, n, pct, rate, eta_text.c_str(),
                f);
  std::snprintf(buf[2], sizeof buf[2], "%lld/%lld %.1f%% ETA %s", d, n, pct, eta_text.c_str());
  std::snprintf(buf[3], sizeof buf[3], "%.1f%% ETA %s", pct, eta_text.c_str());
  // The last column stays free: a line that fills it wraps on some terminals.
  for (const char* text : buf)
    if (width <= 0 || int(std::strlen(text)) < width) return text;
  return std::string(buf[3]).substr(0, std::size_t(std::max(width - 1, 0)));
}

ProgressReporter::ProgressReporter(const ProgressCounters& counters, std::int64_t total, ProgressMode mode,
                                   std::chrono::seconds interval)
    : counters_(counters), total_(total), tty_(isatty(STDERR_FILENO) != 0), start_(std::chrono::steady_clock::now()) {
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
  // Read the width each time: the terminal may have been resized.
  const std::string text =
      line(counters_.done.load(), total_, counters_.failed.load(), s, tty_ ? terminal_width(STDERR_FILENO) : 0);
  if (tty_) std::fprintf(stderr, "\r\033[K%s%s", text.c_str(), final_line ? "\n" : "");
  else std::fprintf(stderr, "progress: %s\n", text.c_str());
  std::fflush(stderr);
}

}  // namespace chaosweep
