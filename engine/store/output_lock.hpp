#pragma once
// One writer per output: a sweep holds OUT.lock for as long as it writes
// OUT.partial, so a second sweep on the same output (a double submission, a
// --resume while the first still runs) is refused instead of interleaving
// rows. flock(2): the kernel drops the lock when its holder dies, kill -9
// included, so a stale lock file never blocks; on NFS, Linux maps flock onto
// POSIX locks, which the server arbitrates across nodes.
#include <stdexcept>
#include <string>

namespace chaosweep {

// Another process holds the lock (bad input: the user asked for two writers).
struct OutputLocked : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class OutputLock {
 public:
  // Locks `output` + ".lock" (creating parent directories). Throws
  // OutputLocked naming the holder, or std::runtime_error when the lock file
  // cannot be written (the output's directory is not writable).
  explicit OutputLock(const std::string& output);
  ~OutputLock();  // removes the lock file, then releases it
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

// Whether a live process writes `output` (holds `output` + ".lock"), asked
// without waiting and without creating anything: `chaosweep status` on a
// shard. A file-only probe: the lock file is opened read-only and
// non-blocking, and a free lock is taken shared for an instant and dropped
// (the OutputLock constructor retries briefly, so a sweep starting in that
// instant is not refused).
struct LockProbe {
  bool held = false;
  std::string holder;  // "process PID on HOST" while held
};
LockProbe probe_output_lock(const std::string& output);

}  // namespace chaosweep
