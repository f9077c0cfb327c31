#include "engine/store/disk_room.hpp"

#include <sys/resource.h>
#include <sys/statvfs.h>

#include <filesystem>
#include <system_error>

namespace chaosweep {

namespace {

std::string size_text(std::uintmax_t bytes) {
  if (bytes < (10u << 20)) return std::to_string((bytes + 1023) >> 10) + " KiB";
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

void check_room(const std::string& file, std::uintmax_t bytes, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::uintmax_t size = fs::exists(file, ec) ? fs::file_size(file, ec) : 0;
  rlimit lim{};
  if (getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY && size + bytes > lim.rlim_cur)
    throw OutOfRoom(file + " would pass this process's file-size limit (ulimit -f: " + std::to_string(lim.rlim_cur) +
                    " bytes; the file has " + std::to_string(size) + ", " + what + " needs up to " +
                    std::to_string(bytes) + ")");
  fs::path dir = fs::path(file).parent_path();
  if (dir.empty()) dir = ".";
  struct statvfs st {};
  if (statvfs(dir.c_str(), &st) != 0) return;  // cannot tell: let the write itself report
  const std::uintmax_t free_bytes = std::uintmax_t(st.f_bavail) * st.f_frsize;
  if (bytes > free_bytes)
    throw OutOfRoom("no room in " + dir.string() + " for " + what + " of " + file + " (needs up to " +
                    size_text(bytes) + ", " + size_text(free_bytes) + " free)");
}

}  // namespace chaosweep
