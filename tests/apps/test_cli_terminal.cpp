// `chaosweep sweep` as seen on a terminal: the live progress line fits the
// terminal's width (a pseudo-terminal of 50 columns), and the summary
// states the elapsed time.
#include <gtest/gtest.h>

#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <regex>
#include <string>
#include <vector>

#include "tests/support/test_util.hpp"

using chaosweep::test::TempDir;

namespace {

struct TerminalRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr as the terminal got them
};

// Runs the binary with `args` on a pseudo-terminal `columns` wide.
TerminalRun run_on_terminal(const std::vector<std::string>& args, unsigned short columns) {
  winsize ws{};
  ws.ws_col = columns;
  ws.ws_row = 24;
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, &ws);
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(CHAOSWEEP_BIN)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(CHAOSWEEP_BIN, argv.data());
    _exit(127);
  }
  TerminalRun out;
  if (pid < 0) return out;
  char buf[4096];
  for (;;) {
    const ssize_t n = read(master, buf, sizeof buf);
    if (n > 0) out.output.append(buf, std::size_t(n));
    else if (n < 0 && errno == EINTR) continue;
    else break;  // EIO once the child has closed the terminal
  }
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  out.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return out;
}

// The demo sweep with live progress on a terminal `columns` wide.
TerminalRun sweep_demo_on_terminal(const TempDir& dir, unsigned short columns) {
  return run_on_terminal({"sweep", std::string(CHAOSWEEP_SOURCE_DIR) + "/experiments/demo.toml", "-o",
                          dir.file("demo.h5"), "--threads", "2", "--progress", "always"},
                         columns);
}

}  // namespace

TEST(CliSweepTerminal, TheLiveProgressLineFitsAFiftyColumnTerminal) {
  TempDir dir;
  const TerminalRun r = sweep_demo_on_terminal(dir, 50);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Each redraw is "\r\033[K" + the line; a line of 50 or more characters
  // would wrap and the next \r would redraw only its second half.
  const std::string text = std::regex_replace(r.output, std::regex("\x1b\\[K"), "");
  int lines = 0;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find_first_of("\r\n", begin), text.size());
    const std::string segment = text.substr(begin, end - begin);
    if (segment.find("ETA") != std::string::npos) {
      ++lines;
      EXPECT_LT(segment.size(), 50u) << "'" << segment << "'";
    }
    begin = end + 1;
  }
  EXPECT_GE(lines, 1) << r.output;  // at least the final line
  EXPECT_NE(r.output.find("280/280 100.0%"), std::string::npos) << r.output;
  // The summary states how long the sweep took.
  EXPECT_TRUE(std::regex_search(r.output, std::regex("\nelapsed     [0-9]+\\.[0-9] s \\(wall clock"))) << r.output;
}

TEST(CliSweepTerminal, AWideTerminalGetsTheFullLine) {
  TempDir dir;
  const TerminalRun r = sweep_demo_on_terminal(dir, 120);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(
      std::regex_search(r.output, std::regex("280/280 runs \\(100\\.0%\\), [0-9]+ runs/s, ETA 0s, [0-9]+ not ok")))
      << r.output;
}
