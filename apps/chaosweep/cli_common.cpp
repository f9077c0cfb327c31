#include "apps/chaosweep/cli_common.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <sstream>

#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace {

std::string flag_of(std::string name) {
  for (char& c : name)
    if (c == '_') c = '-';
  return "--" + name;
}

SpecValue parse_flag_value(const std::string& key, const std::string& text) {
  const ParamInfo* info = find_param(key);
  if (key == "env" || (info && info->kind == ParamInfo::Kind::choice)) return text;
  std::vector<double> parts;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size())
      throw SpecError(flag_of(key) + ": '" + text + "' is not a number" +
                      (key == "start" || key == "size" ? " (or X,Y)" : ""));
    parts.push_back(v);
  }
  if (parts.size() == 1) return parts[0];
  return parts;
}

}  // namespace

void add_param_flags(CLI::App& app, std::map<std::string, std::string>& raw) {
  auto add = [&](const std::string& key, const std::string& help, const std::string& type) {
    app.add_option_function<std::string>(
           flag_of(key), [&raw, key](const std::string& v) { raw[key] = v; }, help)
        ->type_name(type)
        ->group("Run parameters");
  };
  add("env", "environment: \"empty\", a name from experiments/envs, or a .toml path", "NAME|FILE");
  add("size", "map side, m (both axes), or X,Y", "L|X,Y");
  add("start", "start point X,Y, m (default: the environment's start, else 0.5,0.5)", "X,Y");
  add("ic", "initial state x,y,z of the chaotic system (default: the system's; Arnold 0,1,0)", "X,Y,Z");
  RunParams defaults;
  for (const ParamInfo& p : param_table()) {
    std::string help(p.help);
    const double d = p.get(defaults);
    if (p.kind == ParamInfo::Kind::choice) {
      help += " (" + p.range_text() + "; default " + std::string(p.choices[int(d)]) + ")";
    } else if (!std::isnan(d)) {
      help += " (default " + format_number(d) + "; " + p.range_text() + ")";
    }
    add(std::string(p.name), help, p.kind == ParamInfo::Kind::choice ? "NAME" : "NUM");
  }
}

namespace {
// Applies one flag; its errors start with the flag's name (once).
void apply_flag(RunSpec& run, const std::string& key, const std::string& text) {
  try {
    apply_setting(run, key, parse_flag_value(key, text));
  } catch (const SpecError& e) {
    const std::string msg = e.what();
    throw SpecError(msg.rfind("--", 0) == 0 ? msg : flag_of(key) + ": " + msg);
  }
}
}  // namespace

void apply_param_flags(const std::map<std::string, std::string>& raw, RunSpec& run) {
  // Aliases first so that an explicit --size-x etc. wins over --size.
  for (const char* alias : {"env", "size", "start", "ic"})
    if (auto it = raw.find(alias); it != raw.end()) apply_flag(run, it->first, it->second);
  for (const auto& [key, text] : raw)
    if (key != "env" && key != "size" && key != "start" && key != "ic") apply_flag(run, key, text);
}

std::string names_or(const std::vector<std::string>& names) {
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return s;
}

void add_name_and_results(CLI::App& cmd, std::string& name, std::vector<std::string>& files,
                          const std::vector<std::string>& names, bool (*needs_results)(const std::string&)) {
  std::vector<std::string> computed;
  for (const std::string& n : names)
    if (!needs_results(n)) computed.push_back(n);
  cmd.add_option("name", name, names_or(names))->required();
  cmd.add_option("results", files, "result files (.h5); none for " + names_or(computed))->check(CLI::ExistingFile);
}

const CLI::Validator& not_nan() {
  static const CLI::Validator check(
      [](std::string& v) {
        try {
          std::size_t used = 0;
          const double x = std::stod(v, &used);
          if (used == v.size() && !std::isnan(x)) return std::string();
        } catch (const std::exception&) {
        }
        return "'" + v + "' is not a number";
      },
      "NUMBER");
  return check;
}

void add_set_option(CLI::App& cmd, std::vector<std::string>& sets) {
  cmd.add_option("--set", sets,
                 "KEY=VALUE: change the spec's [fixed] setting or [axes] axis KEY (fixed.KEY, axes.KEY to say which; "
                 "sweep.name), e.g. --set sr=4 --set 'A=[0.4, 0.5]'; repeatable; recorded in the stored spec")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

std::vector<SpecOverride> spec_overrides(const std::vector<std::string>& sets) {
  std::vector<SpecOverride> out;
  for (const std::string& s : sets) out.push_back(parse_override(s));
  return out;
}

ProgressMode progress_mode(const std::string& progress, bool quiet) {
  if (progress == "never" || (quiet && progress == "auto")) return ProgressMode::never;
  return progress == "always" ? ProgressMode::always : ProgressMode::automatic;
}

void add_force_flag(CLI::App& cmd, bool& force) {
  cmd.add_flag("--force", force, "replace output files that already exist");
}

void check_output_path(const std::string& path, const std::string& flag) {
  namespace fs = std::filesystem;
  if (path.empty()) throw OutputPathError(flag + ": the output path is empty: give a file name");
  if (fs::is_directory(path))
    throw OutputPathError(flag + ": " + path + " is a directory: give a file name (e.g. " +
                          (fs::path(path) / "results.h5").string() + ")");
  const std::string name = fs::path(path).filename().string();
  if (name.empty() || name == "." || name == "..")
    throw OutputPathError(flag + ": " + path + " names a directory, not a file: give a file name");
}

void check_output_free(const std::string& path, bool force, const std::string& flag, const std::string& more) {
  if (path.empty()) return;
  check_output_path(path, flag);
  if (force || !std::filesystem::exists(path)) return;
  throw OutputExists(flag + ": " + path + " exists; pass --force to replace it" + more);
}

}  // namespace chaosweep
