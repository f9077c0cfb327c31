// The store's HDF5 types and its provenance attributes: written by kind
// (text, int64, boolean), read back as text whatever their kind (so files of
// layout 1, whose attributes are all text, read the same), copied by kind.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "engine/store/h5_detail.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

namespace h5 {

hid_t fixed_text_type(std::size_t size) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, size);
  H5Tset_strpad(t, H5T_STR_NULLTERM);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

hid_t variable_text_type() {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

hid_t bool_type() {
  hid_t t = H5Tenum_create(H5T_NATIVE_INT8);
  const std::int8_t no = 0, yes = 1;
  H5Tenum_insert(t, "FALSE", &no);
  H5Tenum_insert(t, "TRUE", &yes);
  return t;
}

}  // namespace h5

using h5::Handle;

namespace {

// Whether `t` is h5py's boolean: an enum of FALSE = 0 and TRUE = 1.
bool is_bool_enum(hid_t t) {
  if (H5Tget_class(t) != H5T_ENUM || H5Tget_nmembers(t) != 2) return false;
  Handle b{h5::bool_type(), H5Tclose};
  return H5Tequal(t, b.id) > 0;
}

}  // namespace

// Value of the attribute `attr` of `path` as text.
std::string h5::attribute_text(hid_t attr, const std::string& path, const std::string& name) {
  Handle type{H5Aget_type(attr), H5Tclose};
  Handle space{H5Aget_space(attr), H5Sclose};
  auto bad = [&] { h5::input_fail(path + ": attribute '" + name + "' is not one text, number or boolean"); };
  if (H5Sget_simple_extent_npoints(space.id) != 1) bad();
  herr_t rc = -1;
  std::string out;
  H5E_BEGIN_TRY {
    switch (H5Tget_class(type.id)) {
      case H5T_STRING:
        if (H5Tis_variable_str(type.id) > 0) {
          Handle t{h5::variable_text_type(), H5Tclose};
          char* data = nullptr;
          rc = H5Aread(attr, t.id, &data);
          if (rc >= 0 && data) out = data;
          if (data) H5free_memory(data);
        } else {
          const std::size_t size = H5Tget_size(type.id);
          Handle t{h5::fixed_text_type(size + 1), H5Tclose};
          std::vector<char> buf(size + 1, '\0');
          rc = H5Aread(attr, t.id, buf.data());
          out.assign(buf.data(), strnlen(buf.data(), size));
        }
        break;
      case H5T_INTEGER: {
        std::int64_t v = 0;
        rc = H5Aread(attr, H5T_NATIVE_INT64, &v);
        out = std::to_string(v);
        break;
      }
      case H5T_FLOAT: {
        double v = 0;
        rc = H5Aread(attr, H5T_NATIVE_DOUBLE, &v);
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.17g", v);
        out = buf;
        break;
      }
      case H5T_ENUM:
        if (is_bool_enum(type.id)) {
          std::int8_t v = 0;
          Handle b{h5::bool_type(), H5Tclose};
          rc = H5Aread(attr, b.id, &v);
          out = v ? "true" : "false";
        }
        break;
      default:
        break;
    }
  }
  H5E_END_TRY;
  if (rc < 0) bad();
  return out;
}

namespace {

void delete_if_present(hid_t loc, const std::string& name) {
  if (H5Aexists(loc, name.c_str()) > 0) H5Adelete(loc, name.c_str());
}

}  // namespace

void write_attribute(hid_t loc, const Attribute& a) {
  Handle space{H5Screate(H5S_SCALAR), H5Sclose};
  herr_t rc = -1;
  H5E_BEGIN_TRY {
    delete_if_present(loc, a.name);
    if (const std::string* text = std::get_if<std::string>(&a.value)) {
      Handle t{h5::variable_text_type(), H5Tclose};
      Handle attr{H5Acreate2(loc, a.name.c_str(), t.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
      const char* data = text->c_str();
      if (attr.id >= 0) rc = H5Awrite(attr.id, t.id, &data);
    } else if (const std::int64_t* n = std::get_if<std::int64_t>(&a.value)) {
      Handle attr{H5Acreate2(loc, a.name.c_str(), H5T_STD_I64LE, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
      if (attr.id >= 0) rc = H5Awrite(attr.id, H5T_NATIVE_INT64, n);
    } else {
      Handle t{h5::bool_type(), H5Tclose};
      Handle attr{H5Acreate2(loc, a.name.c_str(), t.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
      const std::int8_t v = std::get<bool>(a.value) ? 1 : 0;
      if (attr.id >= 0) rc = H5Awrite(attr.id, t.id, &v);
    }
  }
  H5E_END_TRY;
  if (rc < 0) h5::fail("cannot write attribute " + a.name);
}

void write_text_attribute(hid_t loc, const std::string& name, const std::string& value) {
  write_attribute(loc, {name, value});
}

void copy_attributes(const std::string& from, hid_t to, const std::set<std::string>& skip) {
  Handle file{open_result_file(from), H5Fclose};
  H5O_info_t info;
  if (H5Oget_info2(file.id, &info, H5O_INFO_NUM_ATTRS) < 0) h5::input_fail(from + ": cannot list its attributes");
  for (hsize_t i = 0; i < info.num_attrs; ++i) {
    const ssize_t len = H5Aget_name_by_idx(file.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (len < 0) h5::input_fail(from + ": cannot read the name of attribute " + std::to_string(i));
    std::string name(std::size_t(len) + 1, '\0');
    H5Aget_name_by_idx(file.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(std::size_t(len));
    if (skip.count(name)) continue;
    Handle attr{H5Aopen(file.id, name.c_str(), H5P_DEFAULT), H5Aclose};
    Handle type{H5Aget_type(attr.id), H5Tclose};
    Handle mem{H5Tget_native_type(type.id, H5T_DIR_ASCEND), H5Tclose};
    Handle space{H5Aget_space(attr.id), H5Sclose};
    const hssize_t n = H5Sget_simple_extent_npoints(space.id);
    if (attr.id < 0 || mem.id < 0 || n < 0) h5::input_fail(from + ": cannot read attribute '" + name + "'");
    std::vector<unsigned char> buf(H5Tget_size(mem.id) * std::size_t(n) + 1);
    herr_t rc = -1;
    H5E_BEGIN_TRY {
      if (H5Aread(attr.id, mem.id, buf.data()) >= 0) {
        delete_if_present(to, name);
        Handle out{H5Acreate2(to, name.c_str(), type.id, space.id, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
        rc = out.id >= 0 ? H5Awrite(out.id, mem.id, buf.data()) : -1;
        if (H5Tdetect_class(mem.id, H5T_VLEN) > 0 || H5Tis_variable_str(mem.id) > 0)
          H5Dvlen_reclaim(mem.id, space.id, H5P_DEFAULT, buf.data());
      }
    }
    H5E_END_TRY;
    if (rc < 0) h5::fail("cannot copy attribute '" + name + "' of " + from);
  }
}

std::string join_name_lists(const std::string& a, const std::string& b) {
  std::vector<std::string> names;
  for (const std::string* list : {&a, &b})
    for (std::size_t p = 0; p <= list->size();) {
      std::size_t q = list->find(',', p);
      if (q == std::string::npos) q = list->size();
      const std::size_t from = list->find_first_not_of(' ', p);
      if (from < q) {
        std::string name = list->substr(from, q - from);
        name.erase(name.find_last_not_of(' ') + 1);
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
      }
      p = q + 1;
    }
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string read_attribute(const std::string& path, const std::string& name) {
  Handle file{open_result_file(path), H5Fclose};
  Handle attr{-1, H5Aclose};
  H5E_BEGIN_TRY { attr.id = H5Aopen(file.id, name.c_str(), H5P_DEFAULT); }
  H5E_END_TRY;
  if (attr.id < 0) h5::input_fail(path + " has no attribute '" + name + "' (not a chaosweep result file?)");
  return h5::attribute_text(attr.id, path, name);
}

bool has_attribute(const std::string& path, const std::string& name) {
  Handle file{open_result_file(path), H5Fclose};
  htri_t yes;
  H5E_BEGIN_TRY { yes = H5Aexists(file.id, name.c_str()); }
  H5E_END_TRY;
  return yes > 0;
}

std::int64_t layout_version(const std::string& path) {
  if (!has_attribute(path, "layout_version")) return 1;
  const std::string v = read_attribute(path, "layout_version");
  try {
    std::size_t used = 0;
    const long long n = std::stoll(v, &used);
    if (used == v.size() && n >= 1) return n;
  } catch (const std::exception&) {
  }
  h5::input_fail(path + ": attribute 'layout_version' is '" + v + "', not a layout number");
}

}  // namespace chaosweep
