// The writer's own chunks (row_chunks.hpp: whole chunks encoded, shuffled
// and deflated off the HDF5 library, on many threads) must be the very bytes
// HDF5's write path makes, and read back as the rows given.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <atomic>
#include <cstdint>
#include <vector>

#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"

namespace chaosweep {
namespace {

// Rows 0..n-1 of varied values; a message on the rows `message_every` apart
// (none for 0): a chunk holding one takes HDF5's own write path.
std::vector<RunRow> rows_of(std::size_t n, std::size_t message_every) {
  std::vector<RunRow> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    RunRow& r = out[j];
    r.tuple.run_id = std::int64_t(j);
    r.tuple.env_spec = j % 3 ? "empty" : "maps/a.txt";
    r.tuple.label = "case " + std::to_string(j % 7);
    r.tuple.params = test::small_run(10);
    r.tuple.params.A = 0.3 + 1e-4 * double(j);
    r.result.status = j % 5 ? Status::ok : Status::timeout;
    r.result.coverage_time = 100.0 + 0.5 * double(j);
    r.result.steps = std::int64_t(j * j);
    r.result.wall_time = 1e-3 * double(j);
    if (message_every && j % message_every == 0) r.result.message = "run " + std::to_string(j) + " said something";
  }
  return out;
}

// The stored (filtered) bytes of every chunk of /runs.
std::vector<std::vector<unsigned char>> raw_chunks(const std::string& path) {
  std::vector<std::vector<unsigned char>> out;
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dset = H5Dopen2(file, "/runs", H5P_DEFAULT);
  const hid_t space = H5Dget_space(dset);
  hsize_t rows = 0;
  H5Sget_simple_extent_dims(space, &rows, nullptr);
  for (hsize_t start = 0; start < rows; start += 1024) {
    hsize_t size = 0;
    EXPECT_GE(H5Dget_chunk_storage_size(dset, &start, &size), 0);
    std::vector<unsigned char> bytes(size);
    std::uint32_t mask = 0;
    EXPECT_GE(H5Dread_chunk(dset, H5P_DEFAULT, &start, &mask, bytes.data()), 0);
    EXPECT_EQ(mask, 0u);
    out.push_back(std::move(bytes));
  }
  H5Sclose(space);
  H5Dclose(dset);
  H5Fclose(file);
  return out;
}

// Every column of the file, wall_time included (the same rows were written).
void expect_same_columns(const std::string& a, const std::string& b) {
  const TypedColumns x = read_typed_columns(a), y = read_typed_columns(b);
  EXPECT_EQ(x.rows, y.rows);
  EXPECT_EQ(x.i64, y.i64);
  EXPECT_EQ(x.text, y.text);
  ASSERT_EQ(x.f64.size(), y.f64.size());
  for (const auto& [name, v] : x.f64) {
    const auto& w = y.f64.at(name);
    ASSERT_EQ(v.size(), w.size()) << name;
    for (std::size_t i = 0; i < v.size(); ++i)
      EXPECT_TRUE(v[i] == w[i] || (v[i] != v[i] && w[i] != w[i])) << name << " row " << i;
  }
}

void write(const std::string& path, const std::vector<RunRow>& rows, std::size_t piece, const ParallelFor& parallel) {
  H5RunWriter w(path, H5RunWriter::Mode::create, {{"spec_hash", std::string("x")}}, {{"env", 16}, {"label", 16}});
  for (std::size_t at = 0; at < rows.size(); at += piece) {
    const std::size_t to = std::min(rows.size(), at + piece);
    w.append(std::vector<RunRow>(rows.begin() + std::ptrdiff_t(at), rows.begin() + std::ptrdiff_t(to)), parallel);
  }
  w.finish();
}

TEST(StoreChunks, WholeChunksMadeByTheWriterAreTheBytesHdf5WouldStore) {
  test::TempDir tmp;
  const ThreadBatchEvaluator two(2);
  std::atomic<int> calls{0};
  const ParallelFor parallel = [&](std::size_t n, const std::function<void(std::size_t)>& body) {
    ++calls;
    two.parallel(n, body);
  };
  for (std::size_t message_every : {std::size_t(0), std::size_t(1500)}) {
    const std::vector<RunRow> rows = rows_of(5000, message_every);
    // Appends of 4096 rows: chunks 0-3 whole (made by the writer unless they
    // hold a message); appends of 1000: no piece is a whole chunk, every row
    // goes through H5Dwrite (HDF5's filters).
    write(tmp.file("own.h5"), rows, 4096, parallel);
    write(tmp.file("hdf5.h5"), rows, 1000, nullptr);
    const auto own = raw_chunks(tmp.file("own.h5")), hdf5 = raw_chunks(tmp.file("hdf5.h5"));
    ASSERT_EQ(own.size(), 5u);
    ASSERT_EQ(hdf5.size(), 5u);
    // A chunk holding a message refers to it by its place in the global
    // heap, which differs with the order of the writes: compared as rows.
    for (std::size_t c = 0; c < own.size(); ++c) {
      const bool has_message = message_every && (c * 1024 + message_every - 1) / message_every * message_every <
                                                    std::min<std::size_t>(5000, (c + 1) * 1024);
      if (!has_message) {
        EXPECT_EQ(own[c], hdf5[c]) << "chunk " << c;
      }
    }
    expect_same_columns(tmp.file("own.h5"), tmp.file("hdf5.h5"));
    EXPECT_EQ(read_text_column(tmp.file("own.h5"), "message")[3000], message_every ? "run 3000 said something" : "");
  }
  EXPECT_EQ(calls.load(), 4);  // two appends per file of 4096-row pieces, twice
}

}  // namespace
}  // namespace chaosweep
