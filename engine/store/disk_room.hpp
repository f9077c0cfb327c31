#pragma once
// Room for the next write, checked before it starts. HDF5 cannot take back a
// write that fails halfway (its metadata may be half flushed), so a batch
// that might not fit is not begun: the file keeps every earlier batch and
// stays resumable once space is freed.
#include <cstdint>
#include <stdexcept>
#include <string>

namespace chaosweep {

struct OutOfRoom : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws OutOfRoom when `file` (which may not exist yet) cannot grow by
// `bytes`: the free space of its filesystem for this user, or this process's
// file-size limit (RLIMIT_FSIZE, `ulimit -f`). `what` names the write in
// the message.
void check_room(const std::string& file, std::uintmax_t bytes, const std::string& what = "the next batch");

}  // namespace chaosweep
