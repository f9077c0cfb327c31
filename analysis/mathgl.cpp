#include "analysis/mathgl.hpp"

#include <dlfcn.h>

#include <string>

#include "analysis/result_set.hpp"

namespace chaosweep::mathgl {

namespace {

Api load() {
  // The soname the build found (CMake: the mgl target's), so the library is
  // the one the headers describe.
  void* lib = dlopen(CHAOSWEEP_MGL_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char* why = dlerror();
    throw AnalysisError(std::string("figures need MathGL's library " CHAOSWEEP_MGL_SONAME
                                    " (Debian package libmgl8), which could not be loaded: ") +
                        (why ? why : "unknown error"));
  }
  Api a;
#define CHAOSWEEP_MGL_RESOLVE(name)                                      \
  a.name = reinterpret_cast<decltype(a.name)>(dlsym(lib, "mgl_" #name)); \
  if (!a.name) throw AnalysisError("MathGL's library " CHAOSWEEP_MGL_SONAME " has no function mgl_" #name);
  CHAOSWEEP_MGL_FUNCTIONS(CHAOSWEEP_MGL_RESOLVE)
#undef CHAOSWEEP_MGL_RESOLVE
  return a;  // the library stays loaded for the process
}

}  // namespace

const Api& api() {
  static const Api a = load();  // a failed load throws, and the next call tries again
  return a;
}

}  // namespace chaosweep::mathgl
