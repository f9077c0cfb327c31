#pragma once
// Internals shared by the store's writer, readers and attribute code
// (h5_store*.cpp, h5_attributes.cpp); not for other modules.
#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <type_traits>

#include "engine/store/h5_id.hpp"

namespace chaosweep::h5 {

static_assert(std::is_same_v<hid_t, H5Id>, "H5Id must be hid_t");

// The library failed (not the user's file): "HDF5: ..." messages.
[[noreturn]] inline void fail(const std::string& what) { throw std::runtime_error("HDF5: " + what); }
// A result file cannot be used: the message names the file and what is
// wrong with it (no "HDF5:" prefix: the user gave a file, not a library).
[[noreturn]] inline void input_fail(const std::string& what) { throw std::runtime_error(what); }

// RAII for an HDF5 id and its close function.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), close(c) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id >= 0) close(id);
  }
};

// UTF-8 strings: fixed-length of `size` bytes (NUL-terminated), or variable.
hid_t fixed_text_type(std::size_t size);
hid_t variable_text_type();
// HDF5 has no boolean: h5py's is an enum FALSE = 0, TRUE = 1 over int8.
hid_t bool_type();
// Value of the attribute `attr` of `path` (named `name`) as text: numbers in
// decimal, booleans "true"/"false" (read_attribute).
std::string attribute_text(hid_t attr, const std::string& path, const std::string& name);

}  // namespace chaosweep::h5
