#pragma once
// Build provenance; the definitions are generated at build time from git.
namespace chaosweep {
const char* engine_version();
const char* git_commit();
bool git_dirty();
}  // namespace chaosweep
