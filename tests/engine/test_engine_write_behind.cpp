// Engine: a sweep's writes on a thread of their own (WriteBehind, run_sweep's
// RowWrite) and the store's two halves of an append (prepare, write).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "engine/run/sweep_runner.hpp"
#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/run/write_behind.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/sweep_rows.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::TempDir;

namespace {

// Set once, waited for with a deadline (a test that would hang fails instead).
struct Flag {
  std::mutex m;
  std::condition_variable cv;
  bool set = false;
  void raise() {
    {
      const std::lock_guard<std::mutex> lock(m);
      set = true;
    }
    cv.notify_all();
  }
  bool wait(double seconds) {
    std::unique_lock<std::mutex> lock(m);
    return cv.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return set; });
  }
};

SweepSpec batches_of_cheap_runs() {
  return parse_sweep_spec(
      "[fixed]\nsize = 6\nsr = 2\n[axes]\nA = { start = 0.3, stop = 0.7, num = 8 }\n"
      "B = { start = 0.1, stop = 0.8, num = 10 }\n",
      "write_behind.toml");
}

}  // namespace

TEST(WriteBehind, WritesRunInOrderOneAtATimeWhileTheCallerGoesOn) {
  WriteBehind writes;
  std::mutex m;
  std::vector<int> order;
  std::atomic<int> running{0}, most{0};
  Flag started, release;
  const auto write = [&](int i) {
    return [&, i] {
      const int now = ++running;
      most = std::max(most.load(), now);
      if (i == 0) {
        started.raise();
        release.wait(10);
      }
      {
        const std::lock_guard<std::mutex> lock(m);
        order.push_back(i);
      }
      --running;
    };
  };
  writes.hand_over(write(0));
  writes.hand_over(write(1));  // room for one behind the running write
  ASSERT_TRUE(started.wait(10));
  {
    const std::lock_guard<std::mutex> lock(m);
    EXPECT_TRUE(order.empty()) << "the hand-overs waited for the first write";
  }
  release.raise();
  for (int i = 2; i < 6; ++i) writes.hand_over(write(i));
  writes.wait();
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(most.load(), 1);
}

TEST(WriteBehind, AFailedWriteStopsTheWritesAfterItAndItsErrorReachesTheCaller) {
  WriteBehind writes;
  std::vector<int> done;
  writes.hand_over([&] { done.push_back(0); });
  writes.hand_over([] { throw std::runtime_error("disk full"); });
  // Queued behind the failing one at most: never run.
  bool thrown = false;
  try {
    for (int i = 2; i < 50; ++i) writes.hand_over([&, i] { done.push_back(i); });
    writes.wait();
  } catch (const std::runtime_error& e) {
    thrown = std::string(e.what()) == "disk full";
  }
  EXPECT_TRUE(thrown);
  EXPECT_THROW(writes.wait(), std::runtime_error);
  ASSERT_FALSE(done.empty());
  EXPECT_EQ(done.front(), 0);
  for (std::size_t i = 1; i < done.size(); ++i) ADD_FAILURE() << "write " << done[i] << " ran after a failed one";
}

TEST(SweepRunner, ABatchsRowsAreWrittenWhileTheNextBatchRuns) {
  // The first batch's write holds until the second batch's rows reach the
  // sink: with writes on the sweep's thread, that never happens (the write
  // gives up after 10 s and the test fails).
  const SweepSpec s = batches_of_cheap_runs();
  SweepOptions opt;
  opt.batch_size = 20;
  opt.flush_seconds = 0;
  Flag second_batch;
  bool overlapped = false;
  int pieces = 0;
  std::int64_t written = 0;
  std::vector<std::int64_t> at_write;
  const std::int64_t handed = run_sweep(s, ThreadBatchEvaluator(2), opt, [&](const std::vector<RunRow>& rows) {
    if (++pieces == 2) second_batch.raise();
    const bool first = pieces == 1;
    const std::int64_t from = rows.front().tuple.run_id, n = std::int64_t(rows.size());
    return RowWrite([&, first, from, n] {
      if (first) overlapped = second_batch.wait(10);
      at_write.push_back(from);
      written += n;
    });
  });
  EXPECT_TRUE(overlapped) << "batch 1 reached the sink only after batch 0 was written";
  EXPECT_EQ(handed, s.size());
  EXPECT_EQ(written, s.size()) << "run_sweep returned before its writes finished";
  for (std::size_t i = 0; i < at_write.size(); ++i) EXPECT_EQ(at_write[i], std::int64_t(i) * 20) << "write " << i;
}

TEST(SweepRunner, AWriteThatFailsStopsTheRunsAndItsErrorReachesTheCaller) {
  const SweepSpec s = batches_of_cheap_runs();
  SweepOptions opt;
  opt.batch_size = 10;
  opt.flush_seconds = 0;
  std::int64_t sunk = 0;
  EXPECT_THROW(run_sweep(s, ThreadBatchEvaluator(2), opt,
                         [&](const std::vector<RunRow>& rows) {
                           sunk += std::int64_t(rows.size());
                           return RowWrite([] { throw std::runtime_error("disk full"); });
                         }),
               std::runtime_error);
  EXPECT_LT(sunk, s.size()) << "the runs went on after a write failed";
}

TEST(StoreWriter, RowsPreparedAheadAreWrittenInOrderAsOneAppendWouldWriteThem) {
  TempDir tmp;
  const SweepSpec s = batches_of_cheap_runs();
  const std::vector<RunRow> rows = sweep_rows(s, ThreadBatchEvaluator(2));
  const auto piece = [&](std::size_t from, std::size_t to) {
    return std::vector<RunRow>(rows.begin() + std::ptrdiff_t(from), rows.begin() + std::ptrdiff_t(to));
  };
  {
    H5RunWriter once(tmp.file("once.h5"));
    once.append(rows);
    once.finish();
  }
  H5RunWriter ahead(tmp.file("ahead.h5"));
  // Two prepared before the first is written, the first one's rows
  // overwritten meanwhile: what is written is what was prepared.
  std::vector<RunRow> first = piece(0, 30);
  PreparedRows a = ahead.prepare(first);
  PreparedRows b = ahead.prepare(piece(30, 55));
  first.assign(first.size(), RunRow{});
  ahead.write(std::move(a));
  ahead.write(std::move(b));
  ahead.append(piece(55, rows.size()));
  ahead.finish();
  {
    H5RunWriter wrong(tmp.file("wrong.h5"));
    PreparedRows c = wrong.prepare(piece(0, 30));
    PreparedRows d = wrong.prepare(piece(30, 55));
    EXPECT_THROW(wrong.write(std::move(d)), std::logic_error) << "rows 30.. written before rows 0..";
    EXPECT_EQ(wrong.rows_written(), 0u);
  }
  EXPECT_EQ(read_i64_column(tmp.file("ahead.h5"), "run_id"), read_i64_column(tmp.file("once.h5"), "run_id"));
  // Bit for bit (the runs that miss the target have NaN there).
  const std::vector<double> x = read_f64_column(tmp.file("ahead.h5"), "coverage_time"),
                            y = read_f64_column(tmp.file("once.h5"), "coverage_time");
  ASSERT_EQ(x.size(), y.size());
  EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(double)), 0);
  EXPECT_EQ(read_text_column(tmp.file("ahead.h5"), "status"), read_text_column(tmp.file("once.h5"), "status"));
}
