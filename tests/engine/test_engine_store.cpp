// Engine: the result store's crash safety (rollback driver), layout 2 (text
// never cut, typed provenance, layout 1 still read) and the runner's timed
// hand-over of finished rows.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "engine/rows/result_columns.hpp"
#include "engine/run/sweep_runner.hpp"
#include "engine/spec/sweep_spec.hpp"
#include "engine/spec/text_widths.hpp"
#include "engine/store/h5_store.hpp"
#include "engine/store/rollback_driver.hpp"
#include "tests/support/sweep_rows.hpp"
#include "tests/support/test_util.hpp"

using namespace chaosweep;
using chaosweep::test::read_file;
using chaosweep::test::TempDir;

namespace {

using chaosweep::test::has;

// n hand-made rows from run_id `first`, with the given text.
std::vector<RunRow> rows_of(std::int64_t first, std::size_t n, const std::string& env = "empty",
                            const std::string& label = "", const std::string& message = "") {
  std::vector<RunRow> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    RunRow& r = rows[i];
    r.tuple.run_id = first + std::int64_t(i);
    r.tuple.env_spec = env;
    r.tuple.label = label;
    r.tuple.params = test::small_run(10);
    r.result.status = Status::ok;
    r.result.coverage_time = 100.0 + double(r.tuple.run_id);
    r.result.message = message;
  }
  return rows;
}

// A column of the rows as read_all_columns returns it.
const std::vector<std::string>& text_of(const StoredColumns& c, const std::string& name) {
  for (const auto& [n, v] : c.text)
    if (n == name) return v;
  throw std::runtime_error("no text column " + name);
}
const std::vector<double>& numbers_of(const StoredColumns& c, const std::string& name) {
  for (const auto& [n, v] : c.numeric)
    if (n == name) return v;
  throw std::runtime_error("no numeric column " + name);
}

// In a child process: a write session on `partial` that grows /runs by
// `more` rows and pushes HDF5's metadata into the file, then dies without
// closing it, as a process killed in the middle of a write does.
void die_during_a_write(const std::string& partial, hsize_t more) {
  const pid_t pid = fork();
  if (pid == 0) {
    const hid_t fapl = rollback_fapl();
    const hid_t f = H5Fopen(partial.c_str(), H5F_ACC_RDWR, fapl);
    const hid_t d = H5Dopen2(f, "/runs", H5P_DEFAULT);
    const hid_t space = H5Dget_space(d);
    hsize_t rows = 0;
    H5Sget_simple_extent_dims(space, &rows, nullptr);
    const hsize_t total = rows + more;
    H5Dset_extent(d, &total);
    const hid_t type = H5Dget_type(d), native = H5Tget_native_type(type, H5T_DIR_ASCEND);
    std::vector<unsigned char> zeros(H5Tget_size(native) * more, 0);
    const hid_t fs = H5Dget_space(d), ms = H5Screate_simple(1, &more, nullptr);
    H5Sselect_hyperslab(fs, H5S_SELECT_SET, &rows, nullptr, &more, nullptr);
    H5Dwrite(d, native, ms, fs, H5P_DEFAULT, zeros.data());
    H5Fflush(f, H5F_SCOPE_GLOBAL);  // the new extent, chunk index and header go to the file
    _exit(0);                       // no close: the session never ends
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
}

}  // namespace

TEST(RollbackDriver, AWriteCutShortIsReadAndRolledBackAsOfTheLastClose) {
  TempDir tmp;
  const std::string out = tmp.file("r.h5"), partial = out + ".partial";
  {
    H5RunWriter w(out, H5RunWriter::Mode::create, {{"spec_hash", std::string("abc")}});
    w.append(rows_of(0, 1500));
    w.append(rows_of(1500, 700));  // the last chunk is partly full: the next write rewrites it
  }
  const std::string before = read_file(partial);
  const StoredColumns seen = read_all_columns(partial);
  die_during_a_write(partial, 3000);
  // The dead session changed bytes the file held: they are in the journal.
  ASSERT_TRUE(std::filesystem::exists(journal_path(partial)));
  EXPECT_GT(std::filesystem::file_size(journal_path(partial)), 32u);
  EXPECT_NE(read_file(partial), before);
  // Every reader sees the file as of its last close, and changes nothing.
  EXPECT_EQ(count_rows(partial), 2200);
  const StoredColumns now = read_all_columns(partial);
  EXPECT_EQ(numbers_of(now, "run_id"), numbers_of(seen, "run_id"));
  EXPECT_EQ(text_of(now, "status"), text_of(seen, "status"));
  EXPECT_EQ(read_attribute(partial, "spec_hash"), "abc");
  EXPECT_TRUE(std::filesystem::exists(journal_path(partial)));
  // Rolled back: the very bytes of the last close.
  roll_back(partial);
  EXPECT_FALSE(std::filesystem::exists(journal_path(partial)));
  EXPECT_EQ(read_file(partial), before);
}

TEST(RollbackDriver, AWriterGoesOnFromTheLastCloseAfterAWriteCutShort) {
  TempDir tmp;
  const std::string out = tmp.file("r.h5"), partial = out + ".partial";
  {
    H5RunWriter w(out);
    w.append(rows_of(0, 1100));
  }
  die_during_a_write(partial, 2000);
  {
    H5RunWriter w(out, H5RunWriter::Mode::resume);  // rolls the dead session back first
    EXPECT_EQ(w.rows_written(), 1100u);
    w.append(rows_of(1100, 900));
    w.finish();
  }
  EXPECT_FALSE(std::filesystem::exists(journal_path(partial)));
  const auto ids = read_i64_column(out, "run_id");
  ASSERT_EQ(ids.size(), 2000u);
  for (std::size_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], std::int64_t(i));
}

TEST(H5Store, TextOfAnyLengthIsStoredWholeOrRefusedNamingTheColumn) {
  TempDir tmp;
  const std::string env = "/" + std::string(299, 'e'), label = std::string(300, 'l'),
                    message = "start lies inside obstacle #0 of environment '" + env + "'";
  // Variable-length (no spec to size it) and fixed-length sized to fit.
  for (const auto& widths :
       {std::map<std::string, std::size_t>{}, std::map<std::string, std::size_t>{{"env", 304}, {"label", 301}}}) {
    const std::string out = tmp.file("r" + std::to_string(widths.size()) + ".h5");
    H5RunWriter w(out, H5RunWriter::Mode::create, {}, widths);
    w.append(rows_of(0, 3, env, label, message));
    // One byte too long for a fixed width: refused naming the column, nothing written.
    if (!widths.empty()) {
      try {
        w.append(rows_of(3, 1, env, label + "!", message));
        ADD_FAILURE() << "a label longer than its column was accepted";
      } catch (const std::logic_error& e) {
        EXPECT_TRUE(has(e.what(), "column 'label'")) << e.what();
      }
    }
    w.finish();
    EXPECT_EQ(read_text_column(out, "env"), std::vector<std::string>(3, env));
    EXPECT_EQ(read_text_column(out, "label"), std::vector<std::string>(3, label));
    EXPECT_EQ(read_text_column(out, "message"), std::vector<std::string>(3, message));
    const StoredColumns all = read_all_columns(out);
    EXPECT_EQ(text_of(all, "label"), std::vector<std::string>(3, label));
    EXPECT_EQ(text_of(all, "message"), std::vector<std::string>(3, message));
  }
}

TEST(H5Store, ProvenanceAttributesKeepTheirKind) {
  TempDir tmp;
  const std::string out = tmp.file("r.h5");
  {
    H5RunWriter w(out, H5RunWriter::Mode::create,
                  {{"threads", std::int64_t(2)}, {"git_dirty", true}, {"spec_name", std::string("s")}});
    w.finish();
  }
  const hid_t f = H5Fopen(out.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  auto class_of = [&](const char* name) {
    const hid_t a = H5Aopen(f, name, H5P_DEFAULT), t = H5Aget_type(a);
    const H5T_class_t c = H5Tget_class(t);
    H5Tclose(t);
    H5Aclose(a);
    return c;
  };
  EXPECT_EQ(class_of("threads"), H5T_INTEGER);
  EXPECT_EQ(class_of("layout_version"), H5T_INTEGER);
  EXPECT_EQ(class_of("git_dirty"), H5T_ENUM);  // FALSE/TRUE over int8: h5py's bool
  EXPECT_EQ(class_of("spec_name"), H5T_STRING);
  H5Fclose(f);
  EXPECT_EQ(read_attribute(out, "threads"), "2");
  EXPECT_EQ(read_attribute(out, "git_dirty"), "true");
  EXPECT_EQ(layout_version(out), store_layout_version);
}

TEST(H5Store, FilesOfLayoutOneStayReadableButAreNotResumed) {
  // tests/data/layout1.h5: 6 runs written by chaosweep before layout 2
  // (every text fixed-length, every attribute text).
  const std::string old = CHAOSWEEP_SOURCE_DIR "/tests/data/layout1.h5";
  EXPECT_EQ(layout_version(old), 1);
  EXPECT_EQ(count_rows(old), 6);
  EXPECT_EQ(read_attribute(old, "runs_total"), "6");
  EXPECT_EQ(read_attribute(old, "git_dirty"), "false");
  const StoredColumns all = read_all_columns(old);
  EXPECT_EQ(text_of(all, "label"), std::vector<std::string>(6, "written by chaosweep before layout_version"));
  EXPECT_EQ(text_of(all, "status"), std::vector<std::string>(6, "ok"));
  EXPECT_EQ(read_text_column(old, "env"), std::vector<std::string>(6, "empty"));
  EXPECT_EQ(read_i64_column(old, "ds_index"), (std::vector<std::int64_t>{1, 2, 3, 1, 2, 3}));
  TempDir tmp;
  std::filesystem::copy_file(old, tmp.file("r.h5.partial"));
  try {
    H5RunWriter w(tmp.file("r.h5"), H5RunWriter::Mode::resume);
    ADD_FAILURE() << "a layout 1 file was resumed";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(has(e.what(), "layout 1")) << e.what();
  }
}

TEST(TextWidths, HoldTheEnvironmentAndLabelOfEveryRunOfEveryShippedSpec) {
  int specs = 0;
  for (const auto& entry : std::filesystem::directory_iterator(CHAOSWEEP_SOURCE_DIR "/experiments")) {
    if (entry.path().extension() != ".toml") continue;
    const SweepSpec spec = load_sweep_spec(entry.path().string());
    const auto widths = text_widths(spec);
    ++specs;
    // Every run of the small specs; the first and last 20000 of the others.
    const std::int64_t n = spec.size();
    for (std::int64_t i = 0; i < n; i = (i == 20000 && n > 200000) ? n - 20000 : i + 1) {
      const RunSpec r = spec.run(i);
      ASSERT_LT(r.env.size(), widths.at("env")) << entry.path() << " run " << i;
      ASSERT_LT(r.label.size(), widths.at("label")) << entry.path() << " run " << i;
    }
  }
  EXPECT_GE(specs, 10);
  const SweepSpec parts = parse_sweep_spec(
      "[fixed]\nsr = 2\n[[part]]\nname = \"a part with a long name\"\n[[part]]\nname = \"p2\"\n"
      "[part.axes]\nlabel = [\"short\", 12345.678]\nenv = [\"empty\", \"" +
          std::string(300, 'p') + ".toml\"]\n",
      "x");
  const auto w = text_widths(parts);
  EXPECT_GT(w.at("env"), 308u);
  EXPECT_GT(w.at("label"), std::string("a part with a long name").size());
}

namespace {

// a_values x 8 runs of a few ms each.
SweepSpec few_ms_runs(int a_values) {
  return parse_sweep_spec("[fixed]\nsize = 20\nsr = 1\nmax_time = 4000\n[axes]\nA = { start = 0.3, stop = 0.7, num = " +
                              std::to_string(a_values) + " }\nB = { start = 0.1, stop = 0.8, num = 8 }\n",
                          "timed.toml");
}

// One batch for the whole sweep, handed over every 2 ms (the runs take tens
// of ms in all even on a fast machine, so the hand-over must split them).
SweepOptions one_batch_timed() {
  SweepOptions opt;
  opt.batch_size = 1 << 20;
  opt.flush_seconds = 0.002;
  return opt;
}

}  // namespace

TEST(SweepRunner, FinishedRunsReachTheSinkOnTimeAsARunIdPrefixWhileTheBatchRuns) {
  // One batch: only the timed hand-over can split it.
  const SweepSpec s = few_ms_runs(40);
  const SweepOptions opt = one_batch_timed();
  std::vector<std::size_t> pieces;
  std::vector<RunRow> got;
  const std::int64_t handed = run_sweep(s, ThreadBatchEvaluator(2), opt, [&](const std::vector<RunRow>& rows) {
    pieces.push_back(rows.size());
    got.insert(got.end(), rows.begin(), rows.end());
    return RowWrite{};
  });
  EXPECT_EQ(handed, s.size());
  EXPECT_GT(pieces.size(), 1u) << "the batch reached the sink only at its end";
  SweepOptions whole = opt;
  whole.flush_seconds = 0;
  const auto want = sweep_rows(s, ThreadBatchEvaluator(2), whole);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_EQ(got[i].tuple.run_id, std::int64_t(i));
    for (const Column& c : result_columns())
      if (c.deterministic && c.type != Column::Type::f64) {
        EXPECT_EQ(c.get(got[i]), c.get(want[i])) << "run " << i << " " << c.name;
      } else if (c.deterministic) {
        const double x = std::get<double>(c.get(got[i])), y = std::get<double>(c.get(want[i]));
        EXPECT_TRUE(x == y || (std::isnan(x) && std::isnan(y))) << "run " << i << " " << c.name;
      }
  }
}

// The CLI's sink encodes rows through the evaluator's own parallel(); called
// by the timed hand-over while the batch holds every thread of the arena, it
// must not wait for the batch to end (it did: at 2 threads and more, no row
// reached OUT.partial before the end of a 4096-run batch).
TEST(SweepRunner, ASinkUsingTheEvaluatorsThreadsGetsRowsWhileTheBatchRuns) {
  // A batch of a few hundred ms in many short runs, so that its queue of
  // runs is far from empty when the first piece is due (a blocked
  // parallel() got in only once the queue had run dry).
  const SweepSpec s = few_ms_runs(160);
  SweepOptions opt = one_batch_timed();
  ProgressCounters counters;
  opt.progress = &counters;
  const ThreadBatchEvaluator evaluator(2);
  std::vector<std::int64_t> done_after_piece;
  std::int64_t rows_seen = 0;
  const std::int64_t handed = run_sweep(s, evaluator, opt, [&](const std::vector<RunRow>& rows) -> RowWrite {
    std::vector<int> touched(rows.size(), 0);
    evaluator.parallel(rows.size(), [&](std::size_t i) { touched[i] = 1; });
    for (int t : touched) EXPECT_EQ(t, 1);
    rows_seen += std::int64_t(rows.size());
    done_after_piece.push_back(counters.done.load());
    return RowWrite{};
  });
  EXPECT_EQ(handed, s.size());
  EXPECT_EQ(rows_seen, s.size());
  ASSERT_GT(done_after_piece.size(), 1u) << "the batch reached the sink only at its end";
  EXPECT_LT(done_after_piece.front(), s.size() / 2)
      << "the first timed piece waited in parallel() until the batch's queue of runs ran dry";
}

TEST(SweepRunner, ASinkThatFailsStopsTheRunsAndItsErrorReachesTheCaller) {
  // 1,280 runs: 320 all finished before the first timed piece once, on a
  // loaded machine (the runs got faster); a failing sink stops them, so
  // more cost little.
  const SweepSpec s = few_ms_runs(160);
  SweepOptions opt = one_batch_timed();
  ProgressCounters counters;
  opt.progress = &counters;
  EXPECT_THROW(run_sweep(s, ThreadBatchEvaluator(2), opt,
                         [](const std::vector<RunRow>&) -> RowWrite { throw std::runtime_error("disk full"); }),
               std::runtime_error);
  EXPECT_LT(counters.done.load(), s.size()) << "the runs went on after the sink failed";
}
