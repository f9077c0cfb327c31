// The writer's own chunks (row_chunks.hpp: the chunks a write starts
// encoded, shuffled and deflated off the HDF5 library, on many threads) and merge's (shards'
// chunks unfiltered, interleaved and filtered again) must be the very bytes
// HDF5's write path makes, and read back as the rows given.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "engine/run/thread_batch_evaluator.hpp"
#include "engine/store/chunk_filters.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"
#include "tests/support/test_util.hpp"
#include "tests/support/varied_rows.hpp"

namespace chaosweep {
namespace {

// Rows 0..n-1 of varied values; a message on the rows `message_every` apart
// (none for 0): a chunk holding one takes HDF5's own write path.
std::vector<RunRow> rows_of(std::size_t n, std::size_t message_every) {
  return test::varied_rows(n, {.message_every = message_every, .labels = 7});
}

// Two threads to encode or merge on, counting the calls.
struct CountedThreads {
  ThreadBatchEvaluator two{2};
  std::atomic<int> calls{0};
  ParallelFor parallel = [this](std::size_t n, const std::function<void(std::size_t)>& body) {
    ++calls;
    two.parallel(n, body);
  };
};

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

// /runs of `from` written to a new file `to` by HDF5 alone (one H5Dwrite of
// all rows, the dataset's own creation properties): the bytes HDF5 stores.
void hdf5_copy(const std::string& from, const std::string& to) {
  const hid_t src = H5Fopen(from.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t dset = H5Dopen2(src, "/runs", H5P_DEFAULT);
  const hid_t ftype = H5Dget_type(dset), type = H5Tget_native_type(ftype, H5T_DIR_DEFAULT);
  const hid_t space = H5Dget_space(dset), dcpl = H5Dget_create_plist(dset);
  hsize_t rows = 0;
  H5Sget_simple_extent_dims(space, &rows, nullptr);
  std::vector<unsigned char> buf(rows * H5Tget_size(type));
  ASSERT_GE(H5Dread(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), 0);
  const hid_t dst = H5Fcreate(to.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t maxdims = H5S_UNLIMITED;
  const hid_t out_space = H5Screate_simple(1, &rows, &maxdims);
  const hid_t out = H5Dcreate2(dst, "runs", ftype, out_space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  ASSERT_GE(out, 0);
  ASSERT_GE(H5Dwrite(out, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()), 0);
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, buf.data());
  H5Dclose(out);
  H5Sclose(out_space);
  H5Fclose(dst);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Tclose(type);
  H5Tclose(ftype);
  H5Dclose(dset);
  H5Fclose(src);
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

// Whether chunk c of 1024 rows (of `n`) holds a row with a message.
bool chunk_has_message(std::size_t c, std::size_t n, std::size_t message_every) {
  return message_every &&
         (c * 1024 + message_every - 1) / message_every * message_every < std::min<std::size_t>(n, (c + 1) * 1024);
}

// Shard k of `count` of `rows` (run_ids k, k + count, ...) as a sweep writes it.
void write_shard(const std::string& path, const std::vector<RunRow>& rows, int k, int count) {
  std::vector<RunRow> mine;
  for (std::size_t j = std::size_t(k); j < rows.size(); j += std::size_t(count)) mine.push_back(rows[j]);
  H5RunWriter w(path, H5RunWriter::Mode::create,
                {{"spec_hash", std::string("x")},
                 {"inputs_hash", std::string("y")},
                 {"shard", std::to_string(k) + "/" + std::to_string(count)},
                 {"runs_total", std::int64_t(rows.size())}},
                {{"env", 16}, {"label", 16}});
  w.append(mine);
  w.finish();
}

// HDF5's shuffle by its definition (byte j of element i to j * n + i), for
// sizes that are and are not multiples of the 8 x 8 tiles it is made of.
TEST(StoreChunks, ShuffleIsHdf5sByteTransposeAndUnshuffleItsInverse) {
  for (const std::size_t element : {1u, 7u, 8u, 13u, 936u})
    for (const std::size_t n : {1u, 8u, 1000u, 1024u}) {
      std::vector<unsigned char> in(element * n);
      for (std::size_t b = 0; b < in.size(); ++b) in[b] = static_cast<unsigned char>(b * 131 + b / 7);
      const std::vector<unsigned char> out = shuffled(in, element);
      ASSERT_EQ(out.size(), in.size());
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < element; ++j)
          ASSERT_EQ(out[j * n + i], in[i * element + j]) << element << "-byte elements, " << n << ": " << i << "," << j;
      std::vector<unsigned char> back(in.size());
      unshuffle(out.data(), out.size(), element, back.data());
      EXPECT_EQ(back, in) << element << "-byte elements, " << n;
    }
}

// The stream kept per thread is reset between chunks and set up again when
// the level changes: every chunk is the bytes compress2 makes of it alone.
TEST(StoreChunks, ShuffledAndDeflatedWithAKeptStreamIsEachChunkCompressedAlone) {
  for (const int level : {4, 4, 1, 9, 4})
    for (const std::size_t n : {1u, 1000u, 1024u, 3u}) {
      const std::size_t element = 13;
      std::vector<unsigned char> in(element * n);
      for (std::size_t b = 0; b < in.size(); ++b) in[b] = static_cast<unsigned char>((b * level) % 251 + b / 100);
      const auto kept = shuffled_and_deflated(in.data(), in.size(), element, level);
      EXPECT_EQ(kept, deflated(shuffled(in, element), level)) << "level " << level << ", " << n << " elements";
      std::vector<unsigned char> back(in.size()), unshuffled(in.size());
      ASSERT_TRUE(inflate_exactly(kept.data(), kept.size(), back.data(), back.size()));
      unshuffle(back.data(), back.size(), element, unshuffled.data());
      EXPECT_EQ(unshuffled, in);
    }
}

TEST(StoreChunks, ChunksMadeByTheWriterAreTheBytesHdf5WouldStore) {
  test::TempDir tmp;
  CountedThreads threads;
  const ParallelFor& parallel = threads.parallel;
  const std::atomic<int>& calls = threads.calls;
  for (std::size_t message_every : {std::size_t(0), std::size_t(1500)}) {
    const std::vector<RunRow> rows = rows_of(5000, message_every);
    // The writer makes every chunk that an append's piece starts (unless it
    // holds a message); HDF5 writes the rest of a chunk a piece started
    // short. Appends of 4096 rows: chunks 0-3 whole and chunk 4 (rows
    // 4096-4999, the file's end) padded; of 2548: chunk 2 made with rows
    // 2048-2547, then rows 2548-3071 written into it by HDF5; of 1000 (on
    // one thread): every chunk so. The reference: HDF5 writing all rows.
    write(tmp.file("own.h5"), rows, 4096, parallel);
    write(tmp.file("refilled.h5"), rows, 2548, parallel);
    write(tmp.file("small.h5"), rows, 1000, nullptr);
    hdf5_copy(tmp.file("own.h5"), tmp.file("hdf5.h5"));
    const auto hdf5 = raw_chunks(tmp.file("hdf5.h5"));
    ASSERT_EQ(hdf5.size(), 5u);
    for (const char* name : {"own.h5", "refilled.h5", "small.h5"}) {
      const auto own = raw_chunks(tmp.file(name));
      ASSERT_EQ(own.size(), 5u) << name;
      // A chunk holding a message refers to it by its place in the global
      // heap, which differs with the order of the writes: compared as rows.
      for (std::size_t c = 0; c < own.size(); ++c) {
        if (!chunk_has_message(c, 5000, message_every)) {
          EXPECT_EQ(own[c], hdf5[c]) << name << " chunk " << c;
        }
      }
      expect_same_columns(tmp.file(name), tmp.file("hdf5.h5"));
    }
    EXPECT_EQ(read_text_column(tmp.file("own.h5"), "message")[3000], message_every ? "run 3000 said something" : "");
  }
  EXPECT_EQ(calls.load(), 16);  // two appends, of 4096 and of 2548 rows, twice, each rows then chunks
}

// Merge copies the shards' chunks as bytes (no type conversion) where none
// holds variable-length text: whatever the threads and the block size, the
// merged file is the one file of all rows a sweep writes, to the byte; a
// block whose chunks hold a message is written through HDF5 (its strings read
// from the shards' heaps), and its messages read back (a copied heap id
// would point into the shard's file).
TEST(StoreChunks, MergedShardsAreTheBytesOfOneFileOfAllRows) {
  test::TempDir tmp;
  CountedThreads threads;
  const ParallelFor& parallel = threads.parallel;
  const std::atomic<int>& calls = threads.calls;
  constexpr std::size_t n = 10000;  // 9 whole chunks and a partial one
  for (std::size_t message_every : {std::size_t(0), std::size_t(2500)}) {
    const std::vector<RunRow> rows = rows_of(n, message_every);
    write(tmp.file("whole.h5"), rows, n, parallel);
    std::vector<std::string> shards;
    for (int k = 0; k < 3; ++k) {
      shards.push_back(tmp.file("shard" + std::to_string(k) + ".h5"));
      write_shard(shards.back(), rows, k, 3);
    }
    const auto whole = raw_chunks(tmp.file("whole.h5"));
    ASSERT_EQ(whole.size(), 10u);
    struct Case {
      const char* name;
      MergeOptions options;
    };
    std::vector<Case> cases{{"one thread", {}}, {"two threads", {parallel}}, {"a chunk per block", {parallel, 1}}};
    for (const Case& c : cases) {
      SCOPED_TRACE(std::string(c.name) + ", a message every " + std::to_string(message_every) + " rows");
      const std::string out = tmp.file("merged.h5");
      std::filesystem::remove(out);
      const MergeReport r = merge_results(shards, out, c.options);
      ASSERT_TRUE(r.ok()) << r.text();
      const auto merged = raw_chunks(out);
      ASSERT_EQ(merged.size(), whole.size());
      for (std::size_t k = 0; k < merged.size(); ++k) {
        if (chunk_has_message(k, n, message_every)) continue;
        EXPECT_EQ(merged[k], whole[k]) << "chunk " << k;
      }
      expect_same_columns(out, tmp.file("whole.h5"));
      EXPECT_EQ(read_text_column(out, "message")[5000], message_every ? "run 5000 said something" : "");
      EXPECT_EQ(r.blocks_converted, 0) << "text read from the shards' heaps, not through HDF5's conversion";
    }
  }
  EXPECT_GT(calls.load(), 4);
}

}  // namespace
}  // namespace chaosweep
