// Engine: probing an output's lock (`chaosweep status`) sees a live holder,
// not a lock file left by a killed one nor a FIFO, never waits, and a writer
// starting during a probe is not refused.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "engine/store/output_lock.hpp"
#include "tests/support/test_util.hpp"

using chaosweep::LockProbe;
using chaosweep::OutputLock;
using chaosweep::probe_output_lock;
using chaosweep::test::TempDir;

TEST(OutputLockProbe, SeesALiveHolderOnly) {
  TempDir tmp;
  const std::string out = tmp.file("r.h5");
  EXPECT_FALSE(probe_output_lock(out).held) << "no lock file";
  EXPECT_FALSE(std::filesystem::exists(out + ".lock")) << "the probe creates nothing";
  {
    const OutputLock lock(out);
    const LockProbe p = probe_output_lock(out);
    EXPECT_TRUE(p.held);
    EXPECT_EQ(p.holder.rfind("process " + std::to_string(getpid()) + " on ", 0), 0u) << p.holder;
  }
  chaosweep::test::write_file(out + ".lock", "process 1 on gone\n");  // its holder was killed
  EXPECT_FALSE(probe_output_lock(out).held);
  std::filesystem::remove(out + ".lock");
  ASSERT_EQ(mkfifo((out + ".lock").c_str(), 0644), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(probe_output_lock(out).held) << "a FIFO is no lock";
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

// A shared lock held for a moment, as a probe takes it: the writer waits it
// out instead of reporting another writer; one held for good is refused.
TEST(OutputLockProbe, AWriterStartingDuringAProbeIsNotRefused) {
  TempDir tmp;
  const std::string out = tmp.file("r.h5");
  chaosweep::test::write_file(out + ".lock", "");
  const int fd = open((out + ".lock").c_str(), O_RDONLY | O_CLOEXEC);
  ASSERT_EQ(flock(fd, LOCK_SH | LOCK_NB), 0);
  std::thread release([fd] {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    flock(fd, LOCK_UN);
  });
  EXPECT_NO_THROW(OutputLock lock(out));
  release.join();
  close(fd);  // the writer removed that file on leaving: lock a new one for good
  chaosweep::test::write_file(out + ".lock", "");
  const int held = open((out + ".lock").c_str(), O_RDONLY | O_CLOEXEC);
  ASSERT_EQ(flock(held, LOCK_SH | LOCK_NB), 0);
  EXPECT_THROW(OutputLock lock(out), chaosweep::OutputLocked);
  close(held);
}
