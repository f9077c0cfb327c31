#pragma once
// Reading a file a user names as input: a sweep spec, a spec it extends, an
// environment. Only a regular file is read, and only up to a size cap: a FIFO
// would block the read forever, /dev/zero never ends, and a directory reads
// as an empty file (a spec of one default run, a map without obstacles).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace chaosweep {

struct InputFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A file read as input, as provenance records it.
struct InputRecord {
  std::string path;        // absolute (recorded_path), or a built-in map's name
  std::uint64_t hash = 0;  // fnv1a64 (run_hash.hpp) of its content
};

// `path` made absolute (and normal, symlinks kept) as provenance records it:
// an environment path is found from the working directory, so a relative one
// would not say later which file was read.
std::string recorded_path(const std::string& path);

// The largest spec or environment file read. Far above any real one (the
// shipped files are a few kB; 100,000 obstacles written one a line take
// about 4 MB), far below what would strain memory.
inline constexpr std::size_t max_input_bytes = std::size_t(16) << 20;

// The whole file at `path` (symlinks followed). `what` names it in messages:
// "PATH: cannot open WHAT (No such file or directory)", "PATH: WHAT is a
// directory, not a regular file", "PATH: WHAT is larger than 16 MiB (the
// limit for an input file)". The kind of a file is checked before it is
// opened (a device is never opened) and again on the open descriptor.
std::string read_input_file(const std::string& path, const std::string& what);

}  // namespace chaosweep
