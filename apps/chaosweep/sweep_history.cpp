#include "apps/chaosweep/sweep_history.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "engine/store/provenance.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

// Fields are tab-separated; a tab, newline or backslash in a path is escaped.
std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\\') out += "\\\\";
    else if (c == '\t') out += "\\t";
    else if (c == '\n') out += "\\n";
    else out += c;
  }
  return out;
}

std::string unescape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\' || i + 1 == s.size()) {
      out += s[i];
      continue;
    }
    const char n = s[++i];
    out += n == 't' ? '\t' : n == 'n' ? '\n' : n;
  }
  return out;
}

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> f;
  std::size_t from = 0;
  for (std::size_t at; (at = line.find('\t', from)) != std::string::npos; from = at + 1)
    f.push_back(unescape(line.substr(from, at - from)));
  f.push_back(unescape(line.substr(from)));
  return f;
}

void append_line(const std::vector<std::string>& fields, bool quiet) {
  const std::string path = history_path();
  if (path.empty()) return;
  std::string line;
  for (const std::string& f : fields) line += (line.empty() ? "" : "\t") + escape(f);
  line += "\n";
  std::error_code ec;
  fs::create_directories(fs::path(path).parent_path(), ec);
  // Past a file-size limit (ulimit -f) the write must fail, not kill the sweep.
  const auto old_xfsz = std::signal(SIGXFSZ, SIG_IGN);
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  const bool ok = fd >= 0 && ::write(fd, line.data(), line.size()) == ssize_t(line.size());
  if (fd >= 0) ::close(fd);
  std::signal(SIGXFSZ, old_xfsz);
  if (!ok && !quiet)
    std::cerr << "chaosweep sweep: warning: cannot record the sweep in " << path << " (chaosweep log)\n";
}

}  // namespace

std::string history_path() {
  if (const char* p = std::getenv("CHAOSWEEP_HISTORY")) return p;
  if (const char* x = std::getenv("XDG_STATE_HOME"); x && *x) return std::string(x) + "/chaosweep/history.tsv";
  if (const char* h = std::getenv("HOME"); h && *h) return std::string(h) + "/.local/state/chaosweep/history.tsv";
  return "";
}

std::string record_sweep_start(const SweepRecord& s, bool quiet) {
  const auto ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  const std::string host = host_name();
  const std::string id = host + ":" + std::to_string(::getpid()) + ":" + std::to_string(ns);
  std::error_code ec;
  append_line({"start", id, utc_now(), host, std::to_string(::getpid()), fs::current_path(ec).string(),
               fs::absolute(s.spec, ec).string(), fs::absolute(s.out, ec).string(), s.shard, std::to_string(s.runs),
               s.resume ? "resume" : "new", s.sets},
              quiet);
  return id;
}

void record_sweep_end(const std::string& id, int exit_code, bool quiet) {
  append_line({"end", id, utc_now(), std::to_string(exit_code)}, quiet);
}

std::vector<SweepRecord> read_history(const std::string& path) {
  std::vector<SweepRecord> out;
  std::map<std::string, std::size_t> index;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const auto f = split_tabs(line);
    try {
      if (f.size() == 12 && f[0] == "start") {
        SweepRecord r;
        r.id = f[1];
        r.start_time = f[2];
        r.host = f[3];
        r.pid = std::stoll(f[4]);
        r.cwd = f[5];
        r.spec = f[6];
        r.out = f[7];
        r.shard = f[8];
        r.runs = std::stoll(f[9]);
        r.resume = f[10] == "resume";
        r.sets = f[11];
        index[r.id] = out.size();
        out.push_back(std::move(r));
      } else if (f.size() == 4 && f[0] == "end") {
        if (const auto it = index.find(f[1]); it != index.end()) {
          out[it->second].end_time = f[2];
          out[it->second].exit_code = std::stoi(f[3]);
        }
      }
    } catch (const std::exception&) {
      // a torn or foreign line: skipped
    }
  }
  return out;
}

}  // namespace chaosweep
