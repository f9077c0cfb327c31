#pragma once
// Shared by every test executable, the kernel tests included: scratch
// directories, files and small hand-made runs. Needs only the kernels (no
// HDF5, no binary to run), so that test_kernels links the kernels alone.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {
// GoogleTest prints statuses by name.
inline void PrintTo(Status s, std::ostream* os) { *os << to_string(s); }
}  // namespace chaosweep

namespace chaosweep::test {

// A fresh directory under the system temp dir, removed at scope exit.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

void write_file(const std::string& path, const std::string& text);
std::string read_file(const std::string& path);

// Whether `text` holds `part` (messages, outputs).
inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A small, fast, valid Arnold run: a `side` m map with 1 m cells.
RunParams small_run(double side = 10.0);

// A square map with the given obstacles.
Environment square_map(double side, std::vector<Rect> obstacles = {});

}  // namespace chaosweep::test
