#include "tests/support/test_util.hpp"

#include <sys/resource.h>
#include <sys/wait.h>
#include <csignal>

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>

#include <hdf5.h>

#include "engine/store/h5_store.hpp"

namespace chaosweep::test {

CommandResult run_chaosweep(const std::string& args, const std::string& prefix) {
  TempDir tmp;
  const std::string out = tmp.file("out"), err = tmp.file("err");
  const std::string cmd = prefix + " " + std::string(CHAOSWEEP_BIN) + " " + args + " >" + out + " 2>" + err;
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(out), read_file(err)};
}

int start_chaosweep(const std::string& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec " + std::string(CHAOSWEEP_BIN) + " " + args + " >/dev/null 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return int(pid);
}

int wait_exit(int pid, long* max_rss_kib) {
  int status = 0;
  rusage usage{};
  wait4(pid_t(pid), &status, 0, &usage);
  if (max_rss_kib) *max_rss_kib = usage.ru_maxrss;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

bool wait_for_rows(const std::string& partial, std::int64_t rows, int pid, int* exit_code) {
  for (int i = 0; i < 6000; ++i) {
    if (std::filesystem::exists(partial)) {
      try {
        if (chaosweep::count_rows(partial) >= rows) return true;
      } catch (const std::exception&) {
        // the writer has the file open right now
      }
    }
    int status = 0;
    if (waitpid(pid_t(pid), &status, WNOHANG) == pid) {
      if (exit_code) *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    usleep(10000);
  }
  return false;
}

void write_foreign_file(const std::string& path, const std::string& what) {
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  const hsize_t n = 3;
  hid_t space = H5Screate_simple(1, &n, nullptr);
  if (what == "other-columns") {
    struct Row {
      double a;
      std::int64_t b;
    } data[3] = {{1, 2}, {3, 4}, {5, 6}};
    hid_t t = H5Tcreate(H5T_COMPOUND, sizeof(Row));
    H5Tinsert(t, "a", HOFFSET(Row, a), H5T_NATIVE_DOUBLE);
    H5Tinsert(t, "b", HOFFSET(Row, b), H5T_NATIVE_INT64);
    hid_t d = H5Dcreate2(file, "runs", t, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Dwrite(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(d);
    H5Tclose(t);
  } else {
    const int data[3] = {1, 2, 3};
    hid_t d = H5Dcreate2(file, what == "no-runs" ? "data" : "runs", H5T_NATIVE_INT, space, H5P_DEFAULT, H5P_DEFAULT,
                         H5P_DEFAULT);
    H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
    H5Dclose(d);
  }
  H5Sclose(space);
  H5Fclose(file);
}

std::string small_spec_18_runs(const std::string& name) {
  return "\n[sweep]\nname = \"" + name +
         "\"\n[fixed]\nsize = 12\nsr = 2\nmax_time = 2000\n[axes]\nA = [0.4, 0.5, 0.6]\nB = [0.2, 0.3]\nds_index = [1, "
         "2, 3]\n";
}

std::string tiny_tune_spec() {
  return "[sweep]\nname = \"tiny_tune\"\n"
         "[fixed]\nsize = 10\nsr = 1\nic_jitter = 1e-6\nmax_time = 600\n"
         "[[part]]\nname = \"MZ\"\nfixed = { map_zoning = 1 }\n"
         "case = [ { label = \"open\", env = \"no_obstacles\" }, { label = \"box\", env = \"one_square\" } ]\n"
         "[[part]]\nname = \"plain\"\ncase = [ { label = \"plain\", env = \"no_obstacles\" } ]\n"
         "[tune]\nbudget = 80\nseed = 1\nvalidation_seeds = 6\n"
         "[tune.parameters]\nds_index = [1, 2, 3]\nc = { min = 0.05, max = 1 }\n"
         "[tune.part.MZ]\nparameters = [\"ds_index\", \"c\"]\n[tune.part.plain]\nparameters = []\n";
}

}  // namespace chaosweep::test
