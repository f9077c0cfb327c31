#include "sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "param_table.hpp"

namespace chaosweep {

namespace {

// More runs than this in one spec is almost surely a typo in a range.
constexpr double max_runs = 1e12;
constexpr double max_axis_values = 1e8;

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw SpecError(where + ": " + what);
}

SpecValue to_value(const toml::node& n, const std::string& where) {
  if (n.is_integer() || n.is_floating_point()) return *n.value<double>();
  if (n.is_string()) return *n.value<std::string>();
  if (const toml::array* a = n.as_array()) {
    std::vector<double> out;
    for (const toml::node& e : *a) {
      if (!(e.is_integer() || e.is_floating_point())) fail(where, "a tuple must hold numbers only");
      out.push_back(*e.value<double>());
    }
    return out;
  }
  fail(where, "must be a number, a string or an array of numbers");
}

double as_number(const SpecValue& v, const std::string& key) {
  if (const double* d = std::get_if<double>(&v)) return *d;
  throw SpecError(key + " must be a number, not " + to_text(v));
}

const std::vector<double>& as_tuple(const SpecValue& v, const std::string& key, std::size_t n) {
  const auto* t = std::get_if<std::vector<double>>(&v);
  if (!t || t->size() != n)
    throw SpecError(key + " must be an array of " + std::to_string(n) + " numbers, not " + to_text(v));
  return *t;
}

void set_param(RunParams& p, const std::string& name, const SpecValue& v) {
  const ParamInfo* info = find_param(name);
  if (!info) throw SpecError("unknown key '" + name + "' (known: " + known_keys() + ")");
  double x;
  if (info->kind == ParamInfo::Kind::choice) {
    const auto* s = std::get_if<std::string>(&v);
    auto idx = s ? info->choice_index(*s) : std::nullopt;
    if (!idx) throw SpecError(name + " = " + to_text(v) + " is not allowed: must be " + info->range_text());
    x = *idx;
  } else {
    x = as_number(v, name);
  }
  if (std::string e = info->check(x); !e.empty()) throw SpecError(e);
  info->set(p, x);
}

std::vector<SpecValue> expand_range(const toml::table& r, const std::string& where) {
  for (auto&& [k, n] : r) {
    (void)n;
    const std::string key(k.str());
    if (key != "start" && key != "stop" && key != "step" && key != "num")
      fail(where, "unknown range key '" + key + "' (allowed: start, stop, step or num)");
  }
  auto num = [&](const char* key) -> std::optional<double> {
    const toml::node* n = r.get(key);
    if (!n) return std::nullopt;
    if (!(n->is_integer() || n->is_floating_point())) fail(where + "." + key, "must be a number");
    return *n->value<double>();
  };
  const auto start = num("start"), stop = num("stop"), step = num("step"), count = num("num");
  if (!start || !stop) fail(where, "a range needs start and stop");
  if (step.has_value() == count.has_value()) fail(where, "a range needs exactly one of step or num");
  std::vector<SpecValue> out;
  if (count) {
    if (!(*count >= 1 && *count <= max_axis_values && *count == std::floor(*count)))
      fail(where + ".num", "must be a whole number in [1, 1e8], not " + fmt(*count));
    const auto n = std::int64_t(*count);
    if (n == 1 && *start != *stop) fail(where, "num = 1 needs start == stop");
    for (std::int64_t i = 0; i < n; ++i)
      out.emplace_back(std::in_place_type<double>, n == 1 ? *start : *start + (*stop - *start) * double(i) / double(n - 1));
  } else {
    const double s = *step;
    if (!(std::isfinite(s) && s != 0) || (*stop - *start) * s < 0)
      fail(where + ".step", "must be non-zero and point from start to stop");
    // The stop value is included when it lies on the grid (to 1e-9 of a step).
    const double n = std::floor((*stop - *start) / s + 1e-9) + 1;
    if (n > max_axis_values) fail(where, "gives more than 1e8 values");
    for (std::int64_t i = 0; i < std::int64_t(n); ++i) out.emplace_back(std::in_place_type<double>, *start + double(i) * s);
  }
  return out;
}

}  // namespace

std::string to_text(const SpecValue& v) {
  if (const double* d = std::get_if<double>(&v)) return fmt(*d);
  if (const auto* s = std::get_if<std::string>(&v)) return "\"" + *s + "\"";
  std::string out = "[";
  for (double d : std::get<std::vector<double>>(v)) out += (out.size() > 1 ? ", " : "") + fmt(d);
  return out + "]";
}

std::string known_keys() {
  std::string s = "env, size, start, ic";
  for (const ParamInfo& p : param_table()) s += ", " + std::string(p.name);
  return s;
}

void apply_setting(RunParams& p, std::string& env, const std::string& key, const SpecValue& v) {
  if (key == "env") {
    const auto* s = std::get_if<std::string>(&v);
    if (!s || s->empty()) throw SpecError("env must be an environment name or a path to a .toml file");
    env = *s;
  } else if (key == "size") {
    if (std::holds_alternative<double>(v)) {
      set_param(p, "size_x", v);
      set_param(p, "size_y", v);
    } else {
      const auto& t = as_tuple(v, "size", 2);
      set_param(p, "size_x", t[0]);
      set_param(p, "size_y", t[1]);
    }
  } else if (key == "start") {
    const auto& t = as_tuple(v, "start", 2);
    set_param(p, "start_x", t[0]);
    set_param(p, "start_y", t[1]);
  } else if (key == "ic") {
    const auto& t = as_tuple(v, "ic", 3);
    set_param(p, "ic_x", t[0]);
    set_param(p, "ic_y", t[1]);
    set_param(p, "ic_z", t[2]);
  } else {
    set_param(p, key, v);
  }
}

std::int64_t SweepSpec::size() const {
  std::int64_t n = 1;
  for (const Axis& a : axes) n *= std::int64_t(a.values.size());
  return n;
}

void SweepSpec::run_settings(std::int64_t i, RunParams& p, std::string& env) const {
  p = base;
  env = base_env;
  // Mixed radix, last axis fastest.
  for (std::size_t k = axes.size(); k-- > 0;) {
    const auto n = std::int64_t(axes[k].values.size());
    apply_setting(p, env, axes[k].key, axes[k].values[std::size_t(i % n)]);
    i /= n;
  }
}

SweepSpec parse_sweep_spec(const std::string& text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << e.description() << " (line " << e.source().begin.line << ")";
    fail(source_name, os.str());
  }
  SweepSpec spec;
  spec.text = text;
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    if (key != "sweep" && key != "fixed" && key != "axes")
      fail(source_name, "unknown section '" + key + "' (allowed: [sweep], [fixed], [axes])");
    if (!node.is_table()) fail(source_name, "'" + key + "' must be a table");
  }
  if (const toml::table* s = root["sweep"].as_table()) {
    for (auto&& [k, node] : *s) {
      const std::string key(k.str());
      if (key == "name" || key == "description") {
        if (!node.is_string()) fail(source_name, "sweep." + key + " must be a string");
        (key == "name" ? spec.name : spec.description) = *node.value<std::string>();
      } else {
        fail(source_name, "unknown key 'sweep." + key + "' (allowed: name, description)");
      }
    }
  }
  std::set<std::string> fixed_keys;
  if (const toml::table* f = root["fixed"].as_table()) {
    for (auto&& [k, node] : *f) {
      const std::string key(k.str());
      const std::string where = source_name + ": fixed." + key;
      try {
        apply_setting(spec.base, spec.base_env, key, to_value(node, where));
      } catch (const SpecError& e) {
        fail(where, e.what());
      }
      fixed_keys.insert(key);
    }
  }
  if (const toml::table* a = root["axes"].as_table()) {
    std::vector<std::pair<std::uint32_t, Axis>> ordered;
    for (auto&& [k, node] : *a) {
      Axis axis{std::string(k.str()), {}};
      const std::string where = source_name + ": axes." + axis.key;
      if (fixed_keys.count(axis.key)) fail(where, "is also in [fixed]; give it in one place");
      if (const toml::array* arr = node.as_array()) {
        for (std::size_t i = 0; i < arr->size(); ++i)
          axis.values.push_back(to_value(*arr->get(i), where + "[" + std::to_string(i) + "]"));
      } else if (const toml::table* r = node.as_table()) {
        axis.values = expand_range(*r, where);
      } else {
        fail(where, "must be a list of values or a range {start, stop, step|num}");
      }
      if (axis.values.empty()) fail(where, "is empty: an axis needs at least one value");
      // Check every value now, so a bad value fails before any run starts.
      RunParams scratch = spec.base;
      std::string env = spec.base_env;
      for (std::size_t i = 0; i < axis.values.size(); ++i) {
        try {
          apply_setting(scratch, env, axis.key, axis.values[i]);
        } catch (const SpecError& e) {
          fail(where + "[" + std::to_string(i) + "]", e.what());
        }
      }
      ordered.emplace_back(node.source().begin.line, std::move(axis));
    }
    // toml++ keeps keys sorted; restore the order the user wrote.
    std::stable_sort(ordered.begin(), ordered.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    for (auto& [line, axis] : ordered) spec.axes.push_back(std::move(axis));
  }
  double total = 1;
  for (const Axis& a : spec.axes) total *= double(a.values.size());
  if (total > max_runs) fail(source_name, "expands to " + fmt(total) + " runs (more than 1e12)");
  return spec;
}

SweepSpec load_sweep_spec(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SpecError(path + ": cannot open the sweep spec");
  std::stringstream ss;
  ss << in.rdbuf();
  SweepSpec s = parse_sweep_spec(ss.str(), path);
  if (s.name.empty()) {
    const auto slash = path.find_last_of('/');
    std::string stem = path.substr(slash == std::string::npos ? 0 : slash + 1);
    s.name = stem.substr(0, stem.rfind('.'));
  }
  return s;
}

}  // namespace chaosweep
