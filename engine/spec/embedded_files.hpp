#pragma once
// Files the binary carries in itself (cmake/embed_files.cmake writes their
// bytes into the build at build time, and rebuilds when they change): the
// built-in environments (experiments/envs/*.toml) and the SLURM job templates
// (cluster/*.sbatch.in). A moved or installed binary therefore needs no
// source tree.
#include <optional>
#include <span>
#include <string_view>

namespace chaosweep {

struct EmbeddedFile {
  std::string_view path;  // relative to the source tree, e.g. "cluster/sweep.sbatch.in"
  std::string_view text;
};

// Every embedded file, in path order.
std::span<const EmbeddedFile> embedded_files();

// The text of the embedded file at `path`, or nullopt.
std::optional<std::string_view> embedded_file(std::string_view path);

}  // namespace chaosweep
