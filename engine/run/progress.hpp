#pragma once
// Progress of a long sweep (an observer, in the manner of Taskflow's): the
// workers only bump atomic counters; a reporter thread prints done/total,
// runs/s, ETA and failures to stderr — a live line at most 10 times a second
// on a terminal, a plain line every `interval` otherwise.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace chaosweep {

enum class ProgressMode { automatic, always, never };

// A duration as the progress line shows it: "42s", "3m07s", "2h46m" ("?" if not finite).
std::string duration_text(double seconds);

// The columns of the terminal on `fd` (TIOCGWINSZ), else $COLUMNS, else 80.
int terminal_width(int fd);

struct ProgressCounters {
  std::atomic<std::int64_t> done{0}, failed{0};
};

class ProgressReporter {
 public:
  // total: runs to do.
  ProgressReporter(const ProgressCounters& counters, std::int64_t total, ProgressMode mode,
                   std::chrono::seconds interval = std::chrono::seconds(30));
  ~ProgressReporter();  // prints the final line and joins
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  // The line printed for a given state (tests pin its format). With a
  // width (a terminal's columns; 0: no limit) the line is shorter than it:
  // terser wordings, then fewer fields, then cut, so that it never wraps (a
  // wrapped line is not overwritten by the next, and floods the terminal).
  static std::string line(std::int64_t done, std::int64_t total, std::int64_t failed, double seconds, int width = 0);

 private:
  void loop();
  void print(bool final_line);

  const ProgressCounters& counters_;
  std::int64_t total_;
  bool enabled_, tty_;
  std::chrono::milliseconds period_;
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace chaosweep
