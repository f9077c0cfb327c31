#include "engine/store/input_identity.hpp"

#include <map>
#include <sstream>
#include <stdexcept>

#include "engine/rows/run_hash.hpp"
#include "engine/store/h5_store.hpp"

namespace chaosweep {

namespace {

// One line of input_files: kind, hash, name, path, tab-separated.
struct Line {
  std::string kind, hash, name, path;
};

std::vector<Line> lines_of(const std::string& text) {
  std::vector<Line> out;
  std::istringstream in(text);
  for (std::string row; std::getline(in, row);) {
    Line l;
    std::istringstream cols(row);
    std::getline(cols, l.kind, '\t');
    std::getline(cols, l.hash, '\t');
    std::getline(cols, l.name, '\t');
    std::getline(cols, l.path);
    out.push_back(l);
  }
  return out;
}

std::string what_is(const Line& l) {
  if (l.kind == "env") return "environment '" + l.name + "'";
  if (l.kind == "extends") return "the extended spec";
  return "the sweep spec";
}

}  // namespace

SweepInputs sweep_inputs(const SweepSpec& spec, const EnvironmentCache& cache) {
  SweepInputs in;
  in.spec_hash = hex64(fnv1a64(spec.text));
  for (std::size_t k = 0; k < spec.files.size(); ++k)
    in.files.push_back({k == 0 ? "spec" : "extends", spec.files[k].path, spec.files[k]});
  for (const auto& [name, file] : cache.files()) in.files.push_back({"env", name, file});
  return in;
}

std::string SweepInputs::hash() const {
  // Environments by the name the spec gives and their content, not their
  // path: the same map found under another directory is the same input.
  std::string id = spec_hash + "\n";
  for (const InputFile& f : files)
    if (f.kind == "env") id += f.name + "\t" + hex64(f.file.hash) + "\n";
  return hex64(fnv1a64(id));
}

std::string SweepInputs::text() const {
  std::string t;
  for (const InputFile& f : files) t += f.kind + "\t" + hex64(f.file.hash) + "\t" + f.name + "\t" + f.file.path + "\n";
  return t;
}

std::string changed_inputs(const std::string& before, const std::string& now) {
  std::map<std::pair<std::string, std::string>, Line> old;
  for (const Line& l : lines_of(before)) old[{l.kind, l.name}] = l;
  std::string out;
  const auto add = [&](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
  for (const Line& l : lines_of(now)) {
    const auto it = old.find({l.kind, l.name});
    if (it == old.end()) {
      if (l.kind == "env") add(l.path + " is new (" + what_is(l) + ")");
      continue;
    }
    if (it->second.hash != l.hash) add(l.path + " changed (" + what_is(l) + ")");
    old.erase(it);
  }
  for (const auto& [key, l] : old)
    if (l.kind == "env") add(l.path + " is no longer read (" + what_is(l) + ")");
  return out;
}

void check_same_inputs(const std::string& path, const SweepInputs& now) {
  std::string recorded_files;
  try {
    recorded_files = read_attribute(path, "input_files");
  } catch (const std::exception&) {
    // Made before input files were recorded, or not by chaosweep.
  }
  const std::string changes = changed_inputs(recorded_files, now.text());
  if (read_attribute(path, "spec_hash") != now.spec_hash)
    throw std::runtime_error(path + " holds another spec's runs (spec_hash differs" +
                             (changes.empty() ? "" : ": " + changes) + ")");
  std::string recorded;
  try {
    recorded = read_attribute(path, "inputs_hash");
  } catch (const std::exception&) {
    throw std::runtime_error(path +
                             " does not record its input files (written by an older chaosweep): its "
                             "environment files cannot be checked; pass --force to start over");
  }
  if (recorded != now.hash())
    throw std::runtime_error(
        path + " was made with other input files: " + (changes.empty() ? "inputs_hash differs" : changes) +
        "; restore them, or pass --force to start over");
}

}  // namespace chaosweep
