#include "engine/spec/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace chaosweep {

namespace {

// "a directory", "a FIFO (named pipe)", ...: what a non-regular file is.
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string cap_text() { return std::to_string(max_input_bytes >> 20) + " MiB"; }

[[noreturn]] void refuse(const std::string& path, const std::string& what, const std::string& why) {
  throw InputFileError(path + ": " + what + " " + why);
}

void check_regular(const struct stat& st, const std::string& path, const std::string& what) {
  if (!S_ISREG(st.st_mode)) refuse(path, what, "is " + kind_of(st.st_mode) + ", not a regular file");
  if (std::size_t(st.st_size) > max_input_bytes)
    refuse(path, what, "is larger than " + cap_text() + " (the limit for an input file)");
}

}  // namespace

std::string recorded_path(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path a = std::filesystem::absolute(path, ec);
  return ec ? path : a.lexically_normal().string();
}

std::string read_input_file(const std::string& path, const std::string& what) {
  struct stat before {};
  if (::stat(path.c_str(), &before) != 0) {
    const int err = errno;
    throw InputFileError(path + ": cannot open " + what + " (" + std::strerror(err) + ")");
  }
  check_regular(before, path, what);
  // O_NONBLOCK: should the path have become a FIFO since the stat, opening it
  // does not wait for a writer; the descriptor's own kind is checked below.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    throw InputFileError(path + ": cannot open " + what + " (" + std::strerror(err) + ")");
  }
  std::string text;
  try {
    struct stat st {};
    if (::fstat(fd, &st) != 0) refuse(path, what, std::string("cannot be examined (") + std::strerror(errno) + ")");
    check_regular(st, path, what);
    // Read to the cap and one byte past it: a file that grows while being
    // read (or whose stat size is 0, as in /proc) is still bounded.
    char buf[1 << 16];
    for (;;) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) refuse(path, what, std::string("cannot be read (") + std::strerror(errno) + ")");
      if (n == 0) break;
      text.append(buf, std::size_t(n));
      if (text.size() > max_input_bytes)
        refuse(path, what, "is larger than " + cap_text() + " (the limit for an input file)");
    }
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return text;
}

}  // namespace chaosweep
