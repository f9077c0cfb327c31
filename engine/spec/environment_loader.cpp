#include "engine/spec/environment_loader.hpp"

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include "engine/spec/toml.hpp"

#include "engine/rows/run_hash.hpp"
#include "engine/spec/embedded_files.hpp"
#include "engine/spec/input_file.hpp"
#include "kernels/core/clutter.hpp"
#include "kernels/core/param_table.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

namespace {

// A number for messages, to 6 significant digits ("9.6" for the relative
// 0.8 of a 12 m map, not 9.600000000000001; "inf", "nan").
std::string shown(double v) { return format_number(v, 6); }

[[noreturn]] void env_fail(const std::string& file, const std::string& what) {
  throw std::runtime_error("environment " + file + ": " + what);
}

double number(const toml::node& n, const std::string& file, const std::string& key) {
  if (auto v = n.value<double>()) return *v;
  env_fail(file, "'" + key + "' must be a number");
}

// A number that must be finite (TOML has nan and inf literals).
double finite_number(const toml::node& n, const std::string& file, const std::string& key) {
  const double v = number(n, file, key);
  if (!std::isfinite(v)) env_fail(file, "'" + key + "' = " + shown(v) + " must be a finite number");
  return v;
}

std::pair<double, double> pair_of(const toml::node& n, const std::string& file, const std::string& key) {
  if (n.is_number()) {
    const double v = finite_number(n, file, key);
    return {v, v};
  }
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) env_fail(file, "'" + key + "' must be a number or [x, y]");
  return {finite_number(*a->get(0), file, key + "[0]"), finite_number(*a->get(1), file, key + "[1]")};
}

// "[0, 10] x [0, 10] m": the map's extent, for messages.
std::string map_bounds(const Environment& env) { return "[0, " + shown(env.lx) + "] x [0, " + shown(env.ly) + "] m"; }

toml::table parse_environment_toml(const std::string& text, const std::string& path) {
  try {
    check_toml_text(text);
    toml::table t = toml::parse(text, path);
    check_toml_integers(t);
    return t;
  } catch (const TomlInputError& e) {
    env_fail(path, e.what());
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << e.description() << " at line " << e.source().begin.line;
    env_fail(path, os.str());
  }
}

// The top-level keys: the name, the units (returns whether they are
// relative), and no key outside the allowed ones.
bool read_name_and_units(const toml::table& t, const std::string& path, Environment& env) {
  bool relative = true;
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    if (key == "name") {
      if (!node.is_string()) env_fail(path, "'name' must be a string");
      env.name = *node.value<std::string>();
    } else if (key == "units") {
      const auto u = node.value<std::string>();
      if (!u || (*u != "relative" && *u != "m"))
        env_fail(path, "'units' must be \"relative\" (fractions of the map side) or \"m\"");
      relative = *u == "relative";
    } else if (key != "size" && key != "start" && key != "start_units" && key != "obstacles" && key != "description" &&
               key != "clutter") {
      env_fail(path, "unknown key '" + key +
                         "' (allowed: name, description, units, size, start, start_units, obstacles, "
                         "clutter)");
    }
  }
  return relative;
}

void read_size(const toml::table& t, const std::string& path, bool relative, double size_x, double size_y,
               Environment& env) {
  if (const toml::node* s = t.get("size")) {
    std::tie(env.lx, env.ly) = pair_of(*s, path, "size");
    if (!(env.lx > 0 && env.ly > 0))
      env_fail(path, "'size' = " + shown(env.lx) + " x " + shown(env.ly) + " must be positive");
  } else if (!relative) {
    env_fail(path, "'size' is required when units = \"m\"");
  } else {
    env.lx = size_x;
    env.ly = size_y;
  }
}

void read_start(const toml::table& t, const std::string& path, bool relative, Environment& env) {
  const toml::node* s = t.get("start");
  if (!s) return;
  auto [x, y] = pair_of(*s, path, "start");
  bool start_m = !relative;
  if (const toml::node* su = t.get("start_units")) {
    const auto u = su->value<std::string>();
    if (!u || (*u != "relative" && *u != "m")) env_fail(path, "'start_units' must be \"relative\" or \"m\"");
    start_m = *u == "m";
  }
  env.start = start_m ? std::pair{x, y} : std::pair{x * env.lx, y * env.ly};
}

// obstacles[i] = {x, y, w, h}, in metres (sx, sy: the map side per unit).
Rect read_obstacle(const toml::node& node, const std::string& path, const std::string& where, double sx, double sy) {
  const toml::table* r = node.as_table();
  if (!r) env_fail(path, where + " must be a table {x, y, w, h}");
  double v[4];
  const char* names[4] = {"x", "y", "w", "h"};
  for (int j = 0; j < 4; ++j) {
    const toml::node* n = r->get(names[j]);
    if (!n) env_fail(path, where + " lacks '" + names[j] + "'");
    v[j] = finite_number(*n, path, where + "." + names[j]);
  }
  for (auto&& [k, value] : *r) {
    (void)value;
    const std::string key(k.str());
    if (key != "x" && key != "y" && key != "w" && key != "h")
      env_fail(path, where + " has unknown key '" + key + "' (allowed: x, y, w, h)");
  }
  if (!(v[2] > 0 && v[3] > 0)) env_fail(path, where + ": w and h must be positive");
  return Rect{v[0] * sx, v[1] * sy, (v[0] + v[2]) * sx, (v[1] + v[3]) * sy};
}

void read_obstacles(const toml::table& t, const std::string& path, bool relative, Environment& env) {
  const toml::node* o = t.get("obstacles");
  if (!o) return;
  const double sx = relative ? env.lx : 1.0, sy = relative ? env.ly : 1.0;
  const toml::array* arr = o->as_array();
  if (!arr) env_fail(path, "'obstacles' must be an array of {x, y, w, h} tables");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string where = "obstacles[" + std::to_string(i) + "]";
    const Rect rect = read_obstacle(*arr->get(i), path, where, sx, sy);
    // Every obstacle lies within the map (touching its edge is fine; a
    // relative 0.7 + 0.3 may round above 1, hence the tolerance). Overlapping
    // obstacles are fine: the map is their union (docs/inputs.md).
    const double tol_x = 1e-9 * env.lx, tol_y = 1e-9 * env.ly;
    if (!(rect.x0 >= -tol_x && rect.y0 >= -tol_y && rect.x1 <= env.lx + tol_x && rect.y1 <= env.ly + tol_y)) {
      const bool wholly = rect.x0 >= env.lx || rect.y0 >= env.ly || rect.x1 <= 0 || rect.y1 <= 0;
      env_fail(path, where + " spans [" + shown(rect.x0) + ", " + shown(rect.x1) + "] x [" + shown(rect.y0) + ", " +
                         shown(rect.y1) + "] m: " + (wholly ? "it lies outside" : "it reaches outside") + " the map " +
                         map_bounds(env) +
                         (relative ? " (units = \"relative\": need 0 <= x, x + w <= 1, 0 <= y, y + h <= 1)" : ""));
    }
    env.obstacles.push_back(rect);
  }
}

// A clutter seed: whole and at most 2^53 (number() refuses larger TOML
// integers; a larger float would make the uint64_t conversion undefined).
std::uint64_t clutter_seed(const toml::node& node, const std::string& path, const std::string& where) {
  const double v = number(node, path, where);
  constexpr double exact = 9007199254740992.0;  // 2^53
  if (!(v >= 0 && v <= exact && v == std::floor(v)))
    env_fail(path, where + " = " + shown(v) + " must be a whole number in [0, 2^53]");
  return std::uint64_t(v);
}

// The clutter table's values, in metres (`unit`: metres per unit).
ClutterSpec read_clutter_table(const toml::table& ct, const std::string& path, bool relative, double unit) {
  ClutterSpec spec;
  spec.min_side = 0.03 * (relative ? unit : 50.0);
  spec.max_side = 0.08 * (relative ? unit : 50.0);
  spec.gap = 0.02 * (relative ? unit : 50.0);
  for (auto&& [k, node] : ct) {
    const std::string key(k.str()), where = "clutter." + key;
    if (key == "seed") {
      spec.seed = clutter_seed(node, path, where);
      continue;
    }
    const double v = number(node, path, where);
    if (key == "occupancy") {
      if (!(v >= 0 && v <= 0.6)) env_fail(path, where + " must be in [0, 0.6]");
      spec.occupancy = v;
    } else if (key == "min_side" || key == "max_side" || key == "gap") {
      if (!(v >= 0)) env_fail(path, where + " must be >= 0");
      (key == "min_side" ? spec.min_side : key == "max_side" ? spec.max_side : spec.gap) = v * unit;
    } else {
      env_fail(path, "unknown key '" + where + "' (allowed: seed, occupancy, min_side, max_side, gap)");
    }
  }
  return spec;
}

// Clutter the generator can place in this map.
void check_clutter(const ClutterSpec& spec, const std::string& path, const Environment& env) {
  if (!(spec.min_side > 0 && spec.max_side >= spec.min_side)) env_fail(path, "clutter needs 0 < min_side <= max_side");
  if (!(spec.max_side + 2 * spec.gap < std::min(env.lx, env.ly)))
    env_fail(path, "clutter.max_side + 2 gap = " + shown(spec.max_side + 2 * spec.gap) +
                       " m does not fit in the map (" + shown(env.lx) + " x " + shown(env.ly) + " m)");
  // Squares so small that the occupancy needs more of them than the
  // generator tries are a typo (1e-9 for 0.1), not a map.
  const double most = spec.occupancy * env.lx * env.ly / (spec.min_side * spec.min_side);
  if (most > max_clutter_attempts)
    env_fail(path, "clutter.occupancy = " + shown(spec.occupancy) +
                       " with squares of min_side = " + shown(spec.min_side) + " m takes up to " + shown(most) +
                       " squares (more than " + std::to_string(max_clutter_attempts) +
                       ", the generator's attempts): raise clutter.min_side or lower clutter.occupancy");
}

void read_clutter(const toml::table& t, const std::string& path, bool relative,
                  std::optional<std::uint64_t> clutter_seed, Environment& env) {
  const toml::node* c = t.get("clutter");
  if (!c) {
    if (clutter_seed) env_fail(path, "':SEED' is only for environments with a 'clutter' table");
    return;
  }
  const toml::table* ct = c->as_table();
  if (!ct) env_fail(path, "'clutter' must be a table {seed, occupancy, min_side, max_side, gap}");
  ClutterSpec spec = read_clutter_table(*ct, path, relative, relative ? std::min(env.lx, env.ly) : 1.0);
  check_clutter(spec, path, env);
  if (clutter_seed) spec.seed = *clutter_seed;
  const auto start = env.start.value_or(std::pair{0.5, 0.5});
  for (const Rect& r : generate_clutter(env.lx, env.ly, spec, start.first, start.second)) env.obstacles.push_back(r);
  env.name += ":" + std::to_string(spec.seed);
}

// The file's own start must be a place a run can start from (a run's own
// start, which wins over it, is checked when the run starts).
void check_start(const std::string& path, const Environment& env) {
  if (!env.start) return;
  const auto [x, y] = *env.start;
  const std::string at = "'start' = (" + shown(x) + ", " + shown(y) + ") m";
  if (x < 0 || x > env.lx || y < 0 || y > env.ly) env_fail(path, at + " is outside the map " + map_bounds(env));
  if (const int k = env.obstacle_at(x, y); k >= 0)
    env_fail(path, at + " lies inside obstacles[" + std::to_string(k) + "]");
}

Environment parse_text(const std::string& text, const std::string& path, double size_x, double size_y,
                       std::optional<std::uint64_t> clutter_seed) {
  const toml::table t = parse_environment_toml(text, path);
  Environment env;
  env.name = fs::path(path).stem().string();
  const bool relative = read_name_and_units(t, path, env);
  read_size(t, path, relative, size_x, size_y, env);
  read_start(t, path, relative, env);
  read_obstacles(t, path, relative, env);
  read_clutter(t, path, relative, clutter_seed, env);
  env.index_obstacles();
  check_start(path, env);
  return env;
}

Environment parse_file(const std::string& path, double size_x, double size_y, std::optional<std::uint64_t> clutter_seed,
                       InputRecord* source) {
  std::string text;
  try {
    text = read_input_file(path, "the environment file");
  } catch (const InputFileError& e) {
    throw std::runtime_error(std::string("environment ") + e.what());
  }
  if (source) *source = {recorded_path(path), fnv1a64(text)};
  return parse_text(text, path, size_x, size_y, clutter_seed);
}

}  // namespace

Environment parse_environment(const std::string& text, const std::string& source_name, double size_x, double size_y) {
  return parse_text(text, source_name, size_x, size_y, std::nullopt);
}

std::string find_environment_file(const std::string& name) {
  if (const char* p = std::getenv("CHAOSWEEP_ENV_PATH")) {
    std::stringstream ss(p);
    for (std::string d; std::getline(ss, d, ':');) {
      if (d.empty()) continue;
      const fs::path candidate = fs::path(d) / (name + ".toml");
      if (fs::exists(candidate)) return candidate.string();
    }
  }
  return {};
}

std::optional<std::string_view> builtin_environment(const std::string& name) {
  return embedded_file("experiments/envs/" + name + ".toml");
}

Environment load_environment(const std::string& spec, double size_x, double size_y, InputRecord* source) {
  if (spec == "empty" || spec.empty()) {
    Environment env;
    env.name = "empty";
    env.lx = size_x;
    env.ly = size_y;
    return env;
  }
  // "NAME:SEED" picks the clutter seed of a generated environment.
  std::string base = spec;
  std::optional<std::uint64_t> seed;
  if (const auto colon = spec.rfind(':'); colon != std::string::npos) {
    const std::string digits = spec.substr(colon + 1);
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 18)
      throw std::runtime_error("environment '" + spec + "': the part after ':' must be a clutter seed (digits)");
    seed = std::stoull(digits);
    base = spec.substr(0, colon);
  }
  const bool is_path = base.find('/') != std::string::npos || base.ends_with(".toml");
  const std::string path = is_path ? base : find_environment_file(base);
  if (path.empty() && !is_path)
    if (const auto text = builtin_environment(base)) {
      // A built-in map is an input like a file: its text (this binary's copy)
      // is part of the sweep's identity.
      const std::string name = base + ".toml (built in)";
      if (source) *source = {name, fnv1a64(std::string(*text))};
      return parse_text(std::string(*text), name, size_x, size_y, seed);
    }
  if (path.empty() || !fs::exists(path))
    throw std::runtime_error("environment '" + spec +
                             "' not found: give a path to a .toml file, \"empty\", or a name "
                             "from experiments/envs/");
  return parse_file(path, size_x, size_y, seed, source);
}

namespace {

// A thread's last lookup in some cache (EnvironmentCache::id_; 0: none).
struct LastLookup {
  std::uint64_t cache = 0;
  std::string spec;
  double size_x = 0, size_y = 0;
  std::shared_ptr<const Environment> env;
};
thread_local LastLookup last_lookup;
std::atomic<std::uint64_t> cache_ids{0};

}  // namespace

EnvironmentCache::EnvironmentCache() : id_(++cache_ids) {}

std::shared_ptr<const Environment> EnvironmentCache::get(const std::string& spec, double size_x, double size_y) {
  LastLookup& last = last_lookup;
  // An entry never changes once made, so the one this thread was given last
  // is still this cache's.
  if (last.cache == id_ && last.size_x == size_x && last.size_y == size_y && last.spec == spec) return last.env;
  std::shared_ptr<const Environment> env;
  {
    std::lock_guard lock(mutex_);
    auto key = std::tuple{spec, size_x, size_y};
    auto it = cache_.find(key);
    if (it != cache_.end()) {
      env = it->second;
    } else {
      InputRecord source;
      env = std::make_shared<const Environment>(load_environment(spec, size_x, size_y, &source));
      cache_.emplace(key, env);
      if (!source.path.empty()) files_[spec] = source;
    }
  }
  // The thread's own handle on the entry: copies of it count their owners
  // in a control block of this thread's (an aliasing shared_ptr), not the
  // entry's, whose count every thread's runs would bump at once.
  last = {id_, spec, size_x, size_y,
          std::shared_ptr<const Environment>(std::make_shared<std::shared_ptr<const Environment>>(env), env.get())};
  return last.env;
}

std::map<std::string, InputRecord> EnvironmentCache::files() const {
  std::lock_guard lock(mutex_);
  return files_;
}

}  // namespace chaosweep
