// libFuzzer target: the readers of result files (what merge, compare, table
// and figure are given). The input shapes two HDF5 files through the HDF5
// API (HDF5's own parser is not ours to fuzz): /runs or not, of the store's
// columns and foreign ones, each of a kind the store writes or another
// program might, rows of any values (NaN, huge, text with NULs or invalid
// UTF-8), attributes present or not and of any kind. Half the inputs start
// from a well-formed pair of shards and change a few things, so that merge
// and compare get past their checks. Every reader must succeed or throw
// std::runtime_error naming the problem; anything else (a crash, another
// exception, a sanitizer report, a merged file that does not read back with
// every run) is a bug.
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/result_set.hpp"
#include "engine/store/h5_compare.hpp"
#include "engine/store/h5_merge.hpp"
#include "engine/store/h5_store.hpp"

namespace {

using namespace chaosweep;

enum Kind : int { i64, i32, u64, f64, f32, fixed_text, variable_text, foreign_array, kinds };

const char* const names[] = {"run_id", "param_hash", "status", "coverage_time", "variant", "env",
                             "size_x", "size_y",     "sr",     "label",         "A",       "message",
                             "steps",  "wall_time",  "x"};

hid_t type_of(Kind k, std::size_t text_size, bool utf8) {
  switch (k) {
    case i64:
      return H5Tcopy(H5T_NATIVE_INT64);
    case i32:
      return H5Tcopy(H5T_NATIVE_INT32);
    case u64:
      return H5Tcopy(H5T_NATIVE_UINT64);
    case f64:
      return H5Tcopy(H5T_NATIVE_DOUBLE);
    case f32:
      return H5Tcopy(H5T_NATIVE_FLOAT);
    case fixed_text:
    case variable_text: {
      const hid_t t = H5Tcopy(H5T_C_S1);
      H5Tset_size(t, k == variable_text ? H5T_VARIABLE : text_size);
      if (utf8) H5Tset_cset(t, H5T_CSET_UTF8);
      return t;
    }
    default: {
      const hsize_t two = 2;
      return H5Tarray_create2(H5T_NATIVE_INT32, 1, &two);
    }
  }
}

struct Col {
  std::string name;
  Kind kind;
  std::size_t text_size = 8;
  bool utf8 = true;
};

// A shard-like layout: the columns readers need, of the store's kinds.
std::vector<Col> well_formed() {
  return {{"run_id", i64},
          {"param_hash", i64},
          {"status", fixed_text, 12},
          {"coverage_time", f64},
          {"variant", fixed_text, 48},
          {"env", fixed_text, 8},
          {"size_x", f64},
          {"size_y", f64},
          {"sr", f64},
          {"label", variable_text},
          {"message", variable_text}};
}

// An attribute: of a shaped file mostly the plausible value (as text, or as a
// number when it is one), else absent or of any kind.
void attribute(hid_t file, FuzzedDataProvider& in, const char* name, const std::string& plausible, bool shaped) {
  const hid_t scalar = H5Screate(H5S_SCALAR);
  const bool number = !plausible.empty() && plausible.find_first_not_of("0123456789") == std::string::npos;
  const int pick = shaped && in.ConsumeIntegralInRange(0, 7) != 7 ? (number ? 3 : 1) : in.ConsumeIntegralInRange(0, 6);
  switch (pick) {
    case 0:
      break;  // absent
    case 1:
    case 2: {
      const std::string v = shaped || in.ConsumeBool() ? plausible : in.ConsumeRandomLengthString(40);
      write_attribute(file, {name, v});
      break;
    }
    case 3: {
      std::int64_t v = shaped || in.ConsumeBool() ? std::atoll(plausible.c_str()) : in.ConsumeIntegral<std::int64_t>();
      write_attribute(file, {name, v});
      break;
    }
    case 4:
      write_attribute(file, {name, in.ConsumeBool()});
      break;
    case 5: {
      const double v = in.ConsumeFloatingPoint<double>();
      const hid_t a = H5Acreate2(file, name, H5T_NATIVE_DOUBLE, scalar, H5P_DEFAULT, H5P_DEFAULT);
      H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
      H5Aclose(a);
      break;
    }
    default: {  // two values where one is expected
      const hsize_t two = 2;
      const hid_t space = H5Screate_simple(1, &two, nullptr);
      const std::int64_t v[2] = {1, 2};
      const hid_t a = H5Acreate2(file, name, H5T_NATIVE_INT64, space, H5P_DEFAULT, H5P_DEFAULT);
      H5Awrite(a, H5T_NATIVE_INT64, v);
      H5Aclose(a);
      H5Sclose(space);
    }
  }
  H5Sclose(scalar);
}

// Writes `path` from the input; shard `index` of 2 of a plausible sweep.
void write_file(FuzzedDataProvider& in, const std::string& path, int index) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const bool shaped = !in.ConsumeBool();  // an exhausted input reads as zeros: shaped
  const int runs_total = in.ConsumeIntegralInRange(0, 300);
  const int count = in.ConsumeIntegralInRange(1, 3);
  index = index % count;
  std::vector<Col> cols;
  if (shaped) {
    cols = well_formed();
    for (int changes = in.ConsumeIntegralInRange(0, 3); changes > 0 && !cols.empty(); --changes) {
      const std::size_t at = in.ConsumeIntegralInRange<std::size_t>(0, cols.size() - 1);
      if (in.ConsumeBool()) cols.erase(cols.begin() + std::ptrdiff_t(at));
      else cols[at].kind = Kind(in.ConsumeIntegralInRange(0, kinds - 1));
    }
  } else {
    for (int n = in.ConsumeIntegralInRange(0, 12); n > 0; --n)
      cols.push_back({names[in.ConsumeIntegralInRange<std::size_t>(0, std::size(names) - 1)],
                      Kind(in.ConsumeIntegralInRange(0, kinds - 1)), in.ConsumeIntegralInRange<std::size_t>(1, 64),
                      in.ConsumeBool()});
  }
  if (!cols.empty() && in.ConsumeIntegralInRange(0, 15) != 15) {
    // Member names must differ: HDF5 refuses a repeated one.
    std::vector<Col> unique;
    for (const Col& c : cols) {
      bool seen = false;
      for (const Col& u : unique) seen = seen || u.name == c.name;
      if (!seen) unique.push_back(c);
    }
    cols = unique;
    std::vector<hid_t> types;
    std::vector<std::size_t> offsets;
    std::size_t row = 0;
    for (const Col& c : cols) {
      types.push_back(type_of(c.kind, c.text_size, c.utf8));
      offsets.push_back(row);
      row += H5Tget_size(types.back());
    }
    const hid_t type = H5Tcreate(H5T_COMPOUND, row);
    for (std::size_t k = 0; k < cols.size(); ++k) H5Tinsert(type, cols[k].name.c_str(), offsets[k], types[k]);
    const std::size_t rows =
        shaped ? std::size_t((runs_total - index + count - 1) / count) * std::size_t(index < runs_total)
               : in.ConsumeIntegralInRange<std::size_t>(0, 300);
    const std::size_t rows_kept = shaped && in.ConsumeBool() ? in.ConsumeIntegralInRange<std::size_t>(0, rows) : rows;
    std::vector<unsigned char> buf(row * rows_kept, 0);
    std::vector<std::string> texts;
    texts.reserve(rows_kept * cols.size());
    for (std::size_t r = 0; r < rows_kept; ++r)
      for (std::size_t k = 0; k < cols.size(); ++k) {
        unsigned char* p = buf.data() + r * row + offsets[k];
        const Col& c = cols[k];
        const bool mutate = !shaped || in.ConsumeIntegralInRange(0, 40) == 40;
        if (c.kind == fixed_text || c.kind == variable_text) {
          texts.push_back(mutate ? in.ConsumeRandomLengthString(c.kind == fixed_text ? c.text_size : 200)
                                 : std::string(c.name == "status" ? "ok" : "x"));
          if (c.kind == fixed_text) {
            std::memcpy(p, texts.back().data(), std::min(texts.back().size(), c.text_size));
          } else {
            const char* s = in.ConsumeIntegralInRange(0, 20) == 20 ? nullptr : texts.back().c_str();
            std::memcpy(p, &s, sizeof s);
          }
        } else if (c.kind == foreign_array) {
          std::memset(p, 7, 8);
        } else {
          const std::int64_t id =
              c.name == "run_id" || c.name == "param_hash" ? std::int64_t(index) + std::int64_t(r) * count : 10;
          std::int64_t v = mutate ? in.ConsumeIntegral<std::int64_t>() : id;
          const double d = mutate ? in.ConsumeFloatingPoint<double>() : double(id);
          switch (c.kind) {
            case i64:
            case u64:
              std::memcpy(p, &v, 8);
              break;
            case i32: {
              const std::int32_t w = std::int32_t(v);
              std::memcpy(p, &w, 4);
              break;
            }
            case f64:
              std::memcpy(p, &d, 8);
              break;
            default: {
              const float f = float(d);
              std::memcpy(p, &f, 4);
            }
          }
        }
      }
    const hsize_t dims = rows_kept, maxdims = H5S_UNLIMITED, chunk = 64;
    const hid_t space = H5Screate_simple(1, &dims, &maxdims);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(dcpl, 1, &chunk);
    if (in.ConsumeBool()) H5Pset_deflate(dcpl, 1);
    const hid_t d = H5Dcreate2(file, in.ConsumeIntegralInRange(0, 15) == 15 ? "other" : "runs", type, space,
                               H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (rows_kept > 0) H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Tclose(type);
    for (hid_t t : types) H5Tclose(t);
  }
  attribute(file, in, "spec_hash", "h", shaped);
  attribute(file, in, "inputs_hash", "h", shaped);
  attribute(file, in, "input_files", "", shaped);
  attribute(file, in, "shard", std::to_string(index) + "/" + std::to_string(count), shaped);
  attribute(file, in, "runs_total", std::to_string(runs_total), shaped);
  attribute(file, in, "layout_version", "2", shaped);
  attribute(file, in, "simd_target", "avx2, scalar", shaped);
  H5Fclose(file);
}

template <class F>
void quietly(F&& f) {
  try {
    f();
  } catch (const std::runtime_error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // the fuzzer's own HDF5 calls may fail: quietly
  FuzzedDataProvider in(data, size);
  const std::string a = "fuzz_a.h5", b = "fuzz_b.h5", out = "fuzz_out.h5";
  write_file(in, a, 0);
  write_file(in, b, 1);
  for (const std::string& f : {a, b}) {
    quietly([&] { count_rows(f); });
    quietly([&] { column_names(f); });
    quietly([&] { column_types(f); });
    quietly([&] {
      const StoredColumns c = read_all_columns(f);
      for (const auto& [n, v] : c.numeric)
        if (v.size() != c.rows) std::abort();
      for (const auto& [n, v] : c.text)
        if (v.size() != c.rows) std::abort();
    });
    quietly([&] { read_typed_columns(f); });
    for (const char* column : {"run_id", "env", "status", "coverage_time", "x"}) {
      quietly([&] { read_i64_column(f, column); });
      quietly([&] { read_f64_column(f, column); });
      quietly([&] { read_text_column(f, column); });
    }
    quietly([&] { read_attribute(f, "runs_total"); });
    quietly([&] { layout_version(f); });
    quietly([&] { check_result_columns(f); });
    quietly([&] { ResultSet::load({f}); });
  }
  quietly([&] { ResultSet::load({a, b}); });
  CompareOptions opt;
  quietly([&] { compare_results(a, b, opt).text(); });
  quietly([&] { compare_results(b, a, opt).text(); });
  for (const std::vector<std::string>& inputs : {std::vector<std::string>{a, b}, std::vector<std::string>{a}}) {
    unlink(out.c_str());
    quietly([&] {
      const MergeReport r = merge_results(inputs, out);
      (void)r.text();
      if (r.ok() && count_rows(out) != r.runs_total) std::abort();  // merged, but not every run
    });
  }
  return 0;
}
