#include "engine/store/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <thread>

namespace chaosweep {

namespace {

std::string read_holder(int fd) {
  char buf[256] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  std::string s(buf, n > 0 ? std::size_t(n) : 0);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
  return s.empty() ? "another process" : s;
}

constexpr int probe_retries = 10;  // 20 ms apart

std::string host() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

}  // namespace

OutputLock::OutputLock(const std::string& output) : path_(output + ".lock") {
  const std::filesystem::path parent = std::filesystem::path(output).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create directory " + parent.string() + ": " + ec.message());
  for (;;) {
    fd_ = open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw std::runtime_error("cannot write " + path_ + ": " + std::strerror(errno));
    // A `chaosweep status` probe holds the lock for microseconds: retry a
    // few times before calling the holder another writer.
    int rc = 0;
    for (int tries = 1;; ++tries) {
      rc = flock(fd_, LOCK_EX | LOCK_NB);
      if (rc == 0 || errno != EWOULDBLOCK || tries >= probe_retries) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (rc != 0) {
      const int err = errno;
      const std::string holder = read_holder(fd_);
      close(fd_);
      fd_ = -1;
      if (err == EWOULDBLOCK)
        throw OutputLocked(output + " is being written by " + holder + " (lock " + path_ +
                           "); wait for that sweep to end or stop it");
      throw std::runtime_error("cannot lock " + path_ + ": " + std::strerror(err));
    }
    // A holder that was finishing may have removed the file between our open
    // and our flock: then we hold a lock nobody else can see. Start over.
    struct stat held {
    }, named{};
    if (fstat(fd_, &held) == 0 && stat(path_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
        held.st_dev == named.st_dev)
      break;
    close(fd_);
  }
  const std::string me = "process " + std::to_string(getpid()) + " on " + host() + "\n";
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, me.data(), me.size(), 0) != ssize_t(me.size())) {
    // Only the holder's name is lost; the lock itself holds.
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  unlink(path_.c_str());  // while still locked, so nobody locks the old file after us
  close(fd_);
}

LockProbe probe_output_lock(const std::string& output) {
  const std::string path = output + ".lock";
  // O_NONBLOCK: a FIFO in the lock's place must not hang the open.
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return {};  // no lock file: nobody writes (a holder keeps its file)
  LockProbe p;
  struct stat st {};
  if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    if (flock(fd, LOCK_SH | LOCK_NB) == 0) {
      flock(fd, LOCK_UN);
    } else if (errno == EWOULDBLOCK) {
      p.held = true;
      p.holder = read_holder(fd);
    }
  }
  close(fd);
  return p;
}

}  // namespace chaosweep
