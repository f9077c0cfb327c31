#include "tests/support/kernel_test_util.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <sstream>

namespace chaosweep::test {

namespace fs = std::filesystem;

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = fs::temp_directory_path() / ("chaosweep_test_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
  fs::remove_all(path_);
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void write_file(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

RunParams small_run(double side) {
  RunParams p;
  p.size_x = p.size_y = side;
  p.sr = 1.0;
  p.start_x = p.start_y = 0.5;
  return p;
}

Environment square_map(double side, std::vector<Rect> obstacles) {
  Environment env;
  env.name = "hand-made";
  env.lx = env.ly = side;
  env.obstacles = std::move(obstacles);
  return env;
}

}  // namespace chaosweep::test
