#pragma once
// Lookups in a list of named things (the tables, the figures): one list
// serves the dispatch, the list of names and the error for an unknown name.
#include <string>
#include <vector>

#include "analysis/result_set.hpp"

namespace chaosweep {

// The names of `items` (each with a `name`), in order.
template <class T>
std::vector<std::string> names_of(const std::vector<T>& items) {
  std::vector<std::string> out;
  for (const T& item : items) out.push_back(item.name);
  return out;
}

// The item called `name`; AnalysisError "unknown WHAT 'name' (allowed: ...)" if none.
template <class T>
const T& find_named(const std::vector<T>& items, const std::string& name, const std::string& what) {
  std::string list;
  for (const T& item : items) {
    if (item.name == name) return item;
    list += (list.empty() ? "" : ", ") + item.name;
  }
  throw AnalysisError("unknown " + what + " '" + name + "' (allowed: " + list + ")");
}

}  // namespace chaosweep
