#include "engine/spec/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include "engine/spec/toml.hpp"

#include "engine/rows/run_hash.hpp"
#include "engine/spec/decimal_range.hpp"
#include "engine/spec/spec_overrides.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/math/splitmix.hpp"

namespace chaosweep {

namespace {

// More runs than this in one spec is almost surely a typo in a range.
constexpr double max_runs = 1e12;
constexpr double max_axis_values = 1e8;

std::string fmt(double v) { return format_number(v); }

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw SpecError(where + ": " + what); }

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
    for (double v : DecimalRange::by_count(*start, *stop, n).values()) out.emplace_back(v);
  } else {
    const double s = *step;
    if (!(std::isfinite(s) && s != 0) || (*stop - *start) * s < 0)
      fail(where + ".step", "must be non-zero and point from start to stop");
    const DecimalRange range = DecimalRange::by_step(*start, *stop, s);
    if (range.count() > max_axis_values) fail(where, "gives more than 1e8 values");
    for (double v : range.values()) out.emplace_back(v);
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
  std::string s = "env, label, size, start, ic";
  for (const ParamInfo& p : param_table()) s += ", " + std::string(p.name);
  return s;
}

void apply_setting(RunSpec& r, const std::string& key, const SpecValue& v) {
  RunParams& p = r.params;
  if (key == "env") {
    const auto* s = std::get_if<std::string>(&v);
    if (!s || s->empty()) throw SpecError("env must be an environment name or a path to a .toml file");
    r.env = *s;
  } else if (key == "label") {
    if (const auto* s = std::get_if<std::string>(&v)) r.label = *s;
    else if (const double* d = std::get_if<double>(&v)) r.label = fmt(*d);
    else throw SpecError("label must be a string or a number");
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

std::string Axis::name() const {
  if (kind == "axis") return keys[0];
  std::string s = kind + "(";
  for (std::size_t k = 0; k < keys.size(); ++k) s += (k ? ", " : "") + keys[k];
  return s + ")";
}

std::uint64_t permute_index(std::uint64_t i, std::uint64_t n, std::uint64_t key) {
  // A 4-round Feistel network is a bijection of [0, 4^h) for any round
  // function; values that land at or past n walk on through the cycle until
  // they fall inside, which restricts it to a bijection of [0, n). The
  // domain is under 4n, so a walk is short.
  int half = 1;
  while ((std::uint64_t(1) << (2 * half)) < n) ++half;
  const std::uint64_t mask = (std::uint64_t(1) << half) - 1;
  do {
    std::uint64_t l = i >> half, r = i & mask;
    for (std::uint64_t round = 0; round < 4; ++round) {
      std::uint64_t state = key ^ (round * 0xd1b54a32d192ed03ULL) ^ r;
      const std::uint64_t f = splitmix64(state) & mask;
      const std::uint64_t next = l ^ f;
      l = r;
      r = next;
    }
    i = (l << half) | r;
  } while (i >= n);
  return i;
}

Settings Sampler::at(std::int64_t i) const {
  Settings out;
  out.reserve(dims.size());
  for (const Dim& d : dims) {
    // Point i's stratum (Latin hypercube: a permutation per dimension) and
    // its place inside it, both pure functions of (seed, dimension, i).
    std::uint64_t state = d.jitter_key ^ (std::uint64_t(i) * 0xd6e8feb86659fd93ULL);
    const double u = uniform01(state);
    const double w = lhs ? (double(permute_index(std::uint64_t(i), std::uint64_t(n), d.perm_key)) + u) / double(n) : u;
    if (d.choices.empty()) out.emplace_back(d.key, std::min(d.hi, d.lo + (d.hi - d.lo) * w));
    else out.emplace_back(d.key, d.choices[std::min(d.choices.size() - 1, std::size_t(w * double(d.choices.size())))]);
  }
  return out;
}

std::int64_t SpecPart::own_size() const {
  std::int64_t n = 1;
  for (const Axis& a : axes) n *= std::int64_t(a.size());
  return n;
}

std::int64_t SweepSpec::shared_size() const {
  std::int64_t n = 1;
  for (const Axis& a : axes) n *= std::int64_t(a.size());
  return n;
}

std::int64_t SweepSpec::part_size(std::size_t k) const { return parts.at(k).own_size() * shared_size(); }

std::int64_t SweepSpec::part_offset(std::size_t k) const {
  std::int64_t offset = 0;
  for (std::size_t j = 0; j < k && j < parts.size(); ++j) offset += part_size(j);
  return offset;
}

std::size_t SweepSpec::part_of(std::int64_t run_id) const {
  const std::int64_t shared = shared_size();
  std::int64_t first = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    first += parts[k].own_size() * shared;
    if (run_id < first) return k;
  }
  throw std::out_of_range("run_id " + std::to_string(run_id) + " is past the spec's last part");
}

std::int64_t SweepSpec::size() const {
  if (parts.empty()) return shared_size();
  std::int64_t n = 0;
  for (const SpecPart& p : parts) n += p.own_size();
  return n * shared_size();
}

std::int64_t repeat_seed(std::uint64_t master, std::int64_t run_id) {
  std::uint64_t state = master + std::uint64_t(run_id) * 0x9e3779b97f4a7c15ULL;
  return std::int64_t(splitmix64(state) >> 11);
}

namespace {

// The axes of a run's product: its part's own (slowest), then the shared ones.
std::vector<const Axis*> axes_of(const SweepSpec& spec, const SpecPart* part) {
  std::vector<const Axis*> order;
  if (part)
    for (const Axis& a : part->axes) order.push_back(&a);
  for (const Axis& a : spec.axes) order.push_back(&a);
  return order;
}

// The run at position pos[k] of each axis order[k]: base, the part's fixed
// settings, then each axis's settings in order.
RunSpec compose(const SweepSpec& spec, const SpecPart* part, const std::vector<const Axis*>& order,
                const std::vector<std::size_t>& pos) {
  RunSpec r = spec.base;
  if (part)
    for (const auto& [key, value] : part->fixed) apply_setting(r, key, value);
  for (std::size_t k = 0; k < order.size(); ++k)
    order[k]->visit(pos[k], [&](const std::string& key, const SpecValue& value) { apply_setting(r, key, value); });
  if (part && r.label.empty()) r.label = part->name;
  return r;
}

}  // namespace

RunSpec SweepSpec::run(std::int64_t i) const {
  const std::int64_t run_id = i;
  const SpecPart* part = nullptr;
  if (!parts.empty()) {
    const std::size_t k = part_of(i);
    part = &parts[k];
    i -= part_offset(k);
  }
  const std::vector<const Axis*> order = axes_of(*this, part);
  // Mixed radix, last axis fastest.
  std::vector<std::size_t> pos(order.size());
  for (std::size_t k = order.size(); k-- > 0;) {
    const auto n = std::int64_t(order[k]->size());
    pos[k] = std::size_t(i % n);
    i /= n;
  }
  RunSpec r = compose(*this, part, order, pos);
  if (repeat) r.params.seed = repeat_seed(master_seed, run_id);
  return r;
}

std::vector<MapVariant> SweepSpec::environment_variants() const {
  std::vector<MapVariant> out;
  const auto sets_map = [](const Axis* a) {
    for (const std::string& k : a->keys)
      if (k == "env" || k == "size" || k == "size_x" || k == "size_y") return true;
    return false;
  };
  const std::size_t nparts = parts.empty() ? 1 : parts.size();
  for (std::size_t p = 0; p < nparts; ++p) {
    const SpecPart* part = parts.empty() ? nullptr : &parts[p];
    const std::vector<const Axis*> order = axes_of(*this, part);
    std::vector<std::size_t> map_axes;
    for (std::size_t k = 0; k < order.size(); ++k)
      if (sets_map(order[k])) map_axes.push_back(k);
    // Every combination of the map axes' positions, the other axes at 0.
    std::vector<std::size_t> pos(order.size(), 0);
    for (;;) {
      std::string origin = part ? "part '" + part->name + "'" : "";
      for (std::size_t k : map_axes)
        origin += (origin.empty() ? "" : ", ") + order[k]->name() + "[" + std::to_string(pos[k]) + "]";
      out.push_back({compose(*this, part, order, pos), origin.empty() ? "fixed" : origin});
      std::size_t m = map_axes.size();
      while (m > 0 && ++pos[map_axes[m - 1]] == order[map_axes[m - 1]]->size()) pos[map_axes[--m]] = 0;
      if (m == 0) break;
    }
  }
  return out;
}

namespace {

// Values of one key in [axes] or a zip group: a list, or a range table.
std::vector<SpecValue> axis_values(const toml::node& node, const std::string& where) {
  std::vector<SpecValue> values;
  if (const toml::array* arr = node.as_array()) {
    for (std::size_t i = 0; i < arr->size(); ++i)
      values.push_back(to_value(*arr->get(i), where + "[" + std::to_string(i) + "]"));
  } else if (const toml::table* r = node.as_table()) {
    values = expand_range(*r, where);
  } else {
    fail(where, "must be a list of values or a range {start, stop, step|num}");
  }
  if (values.empty()) fail(where, "is empty: an axis needs at least one value");
  return values;
}

// Where a key is set, for the message when it is set a second time.
struct KeyUse {
  std::string origin;    // "fixed.sr", "axes.c", "zip[0]", "part[1].case", ...
  bool axis = false;     // set by an axis (not a fixed setting)
  bool in_part = false;  // set inside a [[part]]
};
using UsedKeys = std::map<std::string, KeyUse>;

// Records that `key` is set at `use`; a key set twice is an error at `where`.
void claim(UsedKeys& used, const std::string& key, const KeyUse& use, const std::string& where) {
  const auto it = used.find(key);
  if (it == used.end()) {
    used.emplace(key, use);
    return;
  }
  const KeyUse& first = it->second;
  if (use.in_part && first.axis && !first.in_part)
    fail(where, "is a top-level axis (" + first.origin + "), which applies to every part; a part must not set it");
  fail(where, "is also set in " + first.origin + "; give it in one place");
}

// Checks every value of an axis now, so a bad value fails before any run.
// (Samples are checked at their bounds and choices by parse_sample.)
void check_axis(const Axis& axis, const RunSpec& base, const std::string& where) {
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    RunSpec scratch = base;
    for (const auto& [key, value] : axis.values[i]) {
      try {
        apply_setting(scratch, key, value);
      } catch (const SpecError& e) {
        const std::string at = axis.kind == "axis"  ? where + "[" + std::to_string(i) + "]"
                               : axis.kind == "zip" ? where + "." + key + "[" + std::to_string(i) + "]"
                                                    : where + "[" + std::to_string(i) + "]." + key;
        fail(at, e.what());
      }
    }
  }
}

// [sample]: n points, Latin-hypercube ("lhs": each range cut into n equal
// strata, one point per stratum, strata paired by seeded permutations) or
// independent uniform ("random"); a list draws one of its values. One axis.
Axis parse_sample(const toml::table& t, const std::string& where, const KeyUse& use, UsedKeys& used,
                  const RunSpec& base) {
  auto sampler = std::make_shared<Sampler>();
  std::uint64_t seed = 0;
  std::vector<std::pair<std::uint32_t, Sampler::Dim>> dims;
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    if (key == "method") {
      const auto m = node.value<std::string>();
      if (!m || (*m != "lhs" && *m != "random")) fail(where + ".method", "must be \"lhs\" or \"random\"");
      sampler->lhs = *m == "lhs";
    } else if (key == "n" || key == "seed") {
      const auto v = node.value<double>();
      if (!v || !(*v >= 0 && *v == std::floor(*v) && *v < 9.007199254740992e15))
        fail(where + "." + key, "must be a whole number >= 0");
      if (key == "n") sampler->n = std::int64_t(*v);
      else seed = std::uint64_t(*v);
    } else {
      claim(used, key, use, where + "." + key);
      Sampler::Dim d;
      d.key = key;
      // Every value a point can take lies in [min, max] or in the list:
      // checking those here checks every point.
      RunSpec scratch = base;
      const auto check = [&](const SpecValue& v, const std::string& at) {
        try {
          apply_setting(scratch, key, v);
        } catch (const SpecError& e) {
          fail(at, e.what());
        }
      };
      if (const toml::table* r = node.as_table()) {
        const auto lo = (*r)["min"].value<double>(), hi = (*r)["max"].value<double>();
        if (!lo || !hi || r->size() != 2) fail(where + "." + key, "a range is {min = a, max = b}");
        if (!(*lo <= *hi)) fail(where + "." + key, "needs min <= max");
        const ParamInfo* info = find_param(key);
        if (!info || info->kind != ParamInfo::Kind::real)
          fail(where + "." + key, "a {min, max} range needs a real-valued parameter; give a list of values");
        d.lo = *lo;
        d.hi = *hi;
        check(d.lo, where + "." + key + ".min");
        check(d.hi, where + "." + key + ".max");
      } else if (node.is_array()) {
        d.choices = axis_values(node, where + "." + key);
        for (std::size_t c = 0; c < d.choices.size(); ++c)
          check(d.choices[c], where + "." + key + "[" + std::to_string(c) + "]");
      } else {
        fail(where + "." + key, "must be a range {min, max} or a list of values");
      }
      dims.emplace_back(node.source().begin.line, std::move(d));
    }
  }
  if (sampler->n < 1 || sampler->n > 100000000) fail(where + ".n", "must be in [1, 1e8]");
  if (dims.empty()) fail(where, "samples nothing: add parameters as {min, max} or lists");
  std::stable_sort(dims.begin(), dims.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  Axis axis{"sample", {}, {}, {}};
  std::uint64_t state = seed;
  for (auto& [line, d] : dims) {
    axis.keys.push_back(d.key);
    d.perm_key = splitmix64(state);
    d.jitter_key = splitmix64(state);
    sampler->dims.push_back(std::move(d));
  }
  axis.sampler = std::move(sampler);
  return axis;
}

toml::table parse_toml(const std::string& text, const std::string& source_name) {
  try {
    check_toml_text(text);
    toml::table t = toml::parse(text, source_name);
    check_toml_integers(t);
    return t;
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << e.description() << " (line " << e.source().begin.line << ")";
    fail(source_name, os.str());
  } catch (const TomlInputError& e) {
    fail(source_name, e.what());
  }
}

std::string read_text(const std::string& path, const std::string& what) {
  try {
    return read_input_file(path, what);
  } catch (const InputFileError& e) {
    throw SpecError(e.what());
  }
}

// A spec file being read, and the files it is being read for: the `extends`
// chain from the spec given down to it.
struct ChainLink {
  std::string name;  // as messages name it
  std::filesystem::path canonical;
};
using ExtendsChain = std::vector<ChainLink>;

ChainLink link_of(const std::string& path) {
  std::error_code ec;
  std::filesystem::path c = std::filesystem::weakly_canonical(path, ec);
  return {path, ec ? std::filesystem::path(path) : c};
}

}  // namespace

namespace {

using OrderedAxes = std::vector<std::pair<std::uint32_t, Axis>>;

// The axis sections of a table (the root or a [[part]]): [axes], [[zip]],
// `case` and [sample], each value checked against `base`. `at` prefixes
// locations ("spec.toml: " or "spec.toml: part[2]."), `origin` prefixes the
// places recorded in `used` ("" or "part[2]."). Axes come with their line.
void parse_axis_sections(const toml::table& t, const std::string& at, const std::string& origin, bool in_part,
                         const RunSpec& base, UsedKeys& used, OrderedAxes& ordered) {
  if (const toml::table* a = t["axes"].as_table()) {
    for (auto&& [k, node] : *a) {
      const std::string key(k.str());
      const std::string where = at + "axes." + key;
      claim(used, key, {origin + "axes." + key, true, in_part}, where);
      Axis axis{"axis", {key}, {}, {}};
      for (SpecValue& v : axis_values(node, where)) axis.values.push_back({{key, std::move(v)}});
      check_axis(axis, base, where);
      ordered.emplace_back(node.source().begin.line, std::move(axis));
    }
  }
  if (const toml::array* zips = t["zip"].as_array()) {
    for (std::size_t z = 0; z < zips->size(); ++z) {
      const toml::table& zt = *zips->get(z)->as_table();
      const std::string zname = "zip[" + std::to_string(z) + "]";
      const std::string where = at + zname;
      Axis axis{"zip", {}, {}, {}};
      std::vector<std::pair<std::uint32_t, std::pair<std::string, std::vector<SpecValue>>>> cols;
      for (auto&& [k, node] : zt) {
        const std::string key(k.str());
        claim(used, key, {origin + zname, true, in_part}, where + "." + key);
        cols.push_back({node.source().begin.line, {key, axis_values(node, where + "." + key)}});
      }
      if (cols.empty()) fail(where, "is empty");
      std::stable_sort(cols.begin(), cols.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      const std::size_t n = cols[0].second.second.size();
      for (const auto& [line, col] : cols) {
        if (col.second.size() != n)
          fail(where, "lists must have equal lengths: '" + cols[0].second.first + "' has " + std::to_string(n) + ", '" +
                          col.first + "' has " + std::to_string(col.second.size()));
        axis.keys.push_back(col.first);
      }
      axis.values.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        for (const auto& [line, col] : cols) axis.values[i].emplace_back(col.first, col.second[i]);
      check_axis(axis, base, where);
      ordered.emplace_back(zt.source().begin.line, std::move(axis));
    }
  }
  // [[case]] tables: one axis whose positions are the cases, in file order.
  if (const toml::array* cases = t["case"].as_array()) {
    Axis axis{"case", {}, {}, {}};
    std::set<std::string> keys;
    for (std::size_t i = 0; i < cases->size(); ++i) {
      const toml::table& ct = *cases->get(i)->as_table();
      const std::string where = at + "case[" + std::to_string(i) + "]";
      std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::string, SpecValue>>> items;
      for (auto&& [k, node] : ct) {
        const std::string key(k.str());
        // Cases share their keys with one another, not with anything else.
        if (!keys.count(key)) claim(used, key, {origin + "case", true, in_part}, where + "." + key);
        keys.insert(key);
        items.push_back(
            {{node.source().begin.line, node.source().begin.column}, {key, to_value(node, where + "." + key)}});
      }
      std::stable_sort(items.begin(), items.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      Settings settings;
      for (auto& [col, kv] : items) settings.push_back(std::move(kv));
      axis.values.push_back(std::move(settings));
    }
    axis.keys.assign(keys.begin(), keys.end());
    check_axis(axis, base, at + "case");
    if (!axis.values.empty()) ordered.emplace_back(cases->source().begin.line, std::move(axis));
  }
  if (const toml::table* st = t["sample"].as_table()) {
    Axis axis = parse_sample(*st, at + "sample", {origin + "sample", true, in_part}, used, base);
    ordered.emplace_back(st->source().begin.line, std::move(axis));
  }
}

// toml++ keeps keys sorted; restore the order the user wrote.
std::vector<Axis> in_file_order(OrderedAxes ordered) {
  std::stable_sort(ordered.begin(), ordered.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Axis> out;
  for (auto& [line, axis] : ordered) out.push_back(std::move(axis));
  return out;
}

// A [[part]]: name, fixed, axes, zip, case, sample. `used` holds the keys the
// spec sets outside its parts; `names` the names of the parts so far.
SpecPart parse_part(const toml::table& t, std::size_t index, const std::string& source_name, const RunSpec& base,
                    UsedKeys used, const std::vector<std::string>& names) {
  const std::string origin = "part[" + std::to_string(index) + "]";
  const std::string at = source_name + ": " + origin;
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    const std::string where = at + "." + key;
    if (key == "name") {
      if (!node.is_string() || node.value<std::string>()->empty()) fail(where, "must be a non-empty string");
    } else if (key == "fixed" || key == "axes" || key == "sample") {
      if (!node.is_table()) fail(where, "must be a table ([" + std::string("part.") + key + "])");
    } else if (key == "zip" || key == "case") {
      if (!node.is_array_of_tables()) fail(where, "must be written as [[part." + key + "]] tables");
    } else {
      const std::string why = key == "repeat" || key == "extends" ? "; " + key + " belongs to the whole spec"
                              : key == "part"                     ? "; parts do not nest"
                                                                  : "";
      fail(at, "unknown key '" + key + "' (allowed: name, fixed, axes, zip, case, sample" + why + ")");
    }
  }
  SpecPart part;
  const auto name = t["name"].value<std::string>();
  if (!name) fail(at, "needs a name (name = \"...\", unique among the spec's parts)");
  part.name = *name;
  for (std::size_t j = 0; j < names.size(); ++j)
    if (names[j] == part.name)
      fail(at + ".name", "\"" + part.name + "\" is the name of an earlier part; names must be unique");

  RunSpec part_base = base;
  if (const toml::table* f = t["fixed"].as_table()) {
    for (auto&& [k, node] : *f) {
      const std::string key(k.str());
      const std::string where = at + ".fixed." + key;
      claim(used, key, {origin + ".fixed." + key, false, true}, where);
      SpecValue v = to_value(node, where);
      try {
        apply_setting(part_base, key, v);
      } catch (const SpecError& e) {
        fail(where, e.what());
      }
      part.fixed.emplace_back(key, std::move(v));
    }
  }
  OrderedAxes ordered;
  parse_axis_sections(t, at + ".", origin + ".", true, part_base, used, ordered);
  part.axes = in_file_order(std::move(ordered));
  return part;
}

}  // namespace

namespace {

SweepSpec parse_spec(const std::string& text, const std::string& source_name, const std::string& dir,
                     ExtendsChain& chain);

// The top-level sections are known and of the right kind, and they set something.
void check_sections(const toml::table& root, const std::string& source_name) {
  for (auto&& [k, node] : root) {
    const std::string key(k.str());
    if (key == "zip" || key == "case" || key == "part") {
      if (!node.is_array_of_tables()) fail(source_name, "'" + key + "' must be written as [[" + key + "]] tables");
    } else if (key != "sweep" && key != "fixed" && key != "axes" && key != "sample" && key != "repeat" &&
               key != "tune") {
      fail(source_name, "unknown section '" + key +
                            "' (allowed: [sweep], [fixed], [axes], [[zip]], [[case]], [sample], [repeat], [[part]], "
                            "[tune])");
    } else if (!node.is_table()) {
      fail(source_name, "'" + key + "' must be a table");
    }
  }
  // An empty spec (no file, only comments, only empty tables) would be one
  // run of the default parameters: almost surely the wrong file.
  bool empty = true;
  for (auto&& [k, node] : root) {
    if (const toml::table* t = node.as_table()) empty = empty && t->empty();
    else if (const toml::array* a = node.as_array()) empty = empty && a->empty();
  }
  if (empty)
    fail(source_name,
         "the spec is empty (it sets nothing): it would be one run of the default parameters; give "
         "[fixed] settings, [axes] or sweep.extends");
}

void check_sweep_keys(const toml::table& s, const std::string& source_name) {
  for (auto&& [k, node] : s) {
    const std::string key(k.str());
    if (key == "name" || key == "description" || key == "extends") {
      if (!node.is_string()) fail(source_name, "sweep." + key + " must be a string");
    } else {
      fail(source_name, "unknown key 'sweep." + key + "' (allowed: name, description, extends)");
    }
  }
}

// The spec named by sweep.extends (`extends`, relative to `dir`), parsed; a
// chain that comes back to one of its specs would recurse forever.
SweepSpec parse_extended(const std::string& extends, const std::string& source_name, const std::string& dir,
                         ExtendsChain& chain) {
  const std::string path = extends.starts_with("/") ? extends : dir + "/" + extends;
  const ChainLink link = link_of(path);
  for (std::size_t k = 0; k < chain.size(); ++k) {
    if (chain[k].canonical != link.canonical) continue;
    if (k + 1 == chain.size())
      fail(source_name + ": sweep.extends", "\"" + extends + "\" is this spec itself: a spec cannot extend itself");
    std::string cycle;
    for (std::size_t j = k; j < chain.size(); ++j) cycle += chain[j].name + " -> ";
    fail(source_name + ": sweep.extends", "\"" + extends + "\" makes a cycle of extended specs: " + cycle + path);
  }
  const std::string parent_text = read_text(path, "the spec named by sweep.extends");
  const auto slash = path.find_last_of('/');
  chain.push_back(link);
  SweepSpec parent = parse_spec(parent_text, path, slash == std::string::npos ? "." : path.substr(0, slash), chain);
  chain.pop_back();
  parent.files.insert(parent.files.begin(), InputRecord{recorded_path(path), fnv1a64(parent_text)});
  return parent;
}

// Starts `spec` from the extended one: its fixed settings, axes and parts
// come first. `used` gets the keys its axes set; `part_keys` those its
// parts set (the top level must not set them too).
void extend_from(SweepSpec& spec, const SweepSpec& parent, const std::string& extends, const toml::table& root,
                 const std::string& source_name, UsedKeys& used, UsedKeys& part_keys) {
  spec.files.insert(spec.files.end(), parent.files.begin(), parent.files.end());
  if (parent.repeat && root["repeat"]) fail(source_name + ": repeat", "the extended spec has a [repeat] already");
  spec.base = parent.base;
  spec.axes = parent.axes;
  spec.parts = parent.parts;
  spec.repeat = parent.repeat;
  spec.master_seed = parent.master_seed;
  for (const Axis& a : parent.axes)
    for (const std::string& key : a.keys) used.emplace(key, KeyUse{"an axis of the extended spec", true, false});
  for (const SpecPart& p : parent.parts) {
    const KeyUse use{"part \"" + p.name + "\" of the extended spec", false, true};
    for (const auto& [key, value] : p.fixed) part_keys.emplace(key, use);
    for (const Axis& a : p.axes)
      for (const std::string& key : a.keys) part_keys.emplace(key, use);
  }
  if (spec.description.empty()) spec.description = parent.description;
  spec.text = "# --- extends " + extends + " ---\n" + parent.text + "# --- " + source_name + " ---\n";
}

// [fixed]: settings of the base run; each key set in one place only.
void read_fixed(const toml::table& f, const std::string& source_name, SweepSpec& spec, UsedKeys& top) {
  for (auto&& [k, node] : f) {
    const std::string key(k.str());
    const std::string where = source_name + ": fixed." + key;
    if (const auto it = top.find(key); it != top.end())
      fail(where, "is also set by " + it->second.origin + "; give it in one place");
    const SpecValue v = to_value(node, where);  // its errors name `where` already
    try {
      apply_setting(spec.base, key, v);
    } catch (const SpecError& e) {
      fail(where, e.what());
    }
  }
  for (auto&& [k, node] : f) {
    const std::string key(k.str());
    top.emplace(key, KeyUse{"fixed." + key, false, false});
  }
}

// [repeat]: count runs of each point, every run's seed from the run_id.
void read_repeat(const toml::table& t, const std::string& source_name, SweepSpec& spec, UsedKeys& top,
                 OrderedAxes& ordered) {
  const std::string where = source_name + ": repeat";
  if (top.count("seed")) fail(where, "sets every run's seed: 'seed' must not be given elsewhere");
  top.emplace("seed", KeyUse{"repeat", true, false});
  std::int64_t count = 0;
  for (auto&& [k, node] : t) {
    const std::string key(k.str());
    const auto v = node.value<double>();
    if (!v || !(*v >= 0 && *v == std::floor(*v) && *v < 9.007199254740992e15))
      fail(where + "." + key, "must be a whole number >= 0");
    if (key == "count") count = std::int64_t(*v);
    else if (key == "seed") spec.master_seed = std::uint64_t(*v);
    else fail(where, "unknown key '" + key + "' (allowed: count, seed)");
  }
  if (count < 1 || count > 100000000) fail(where + ".count", "must be in [1, 1e8]");
  spec.repeat = true;
  // Its positions set nothing themselves (the seed comes from the run_id):
  // a sampler of no dimensions, so count costs no memory.
  auto positions = std::make_shared<Sampler>();
  positions->n = count;
  Axis axis{"repeat", {"seed"}, {}, std::move(positions)};
  ordered.emplace_back(t.source().begin.line, std::move(axis));
}

void check_run_count(const SweepSpec& spec, const std::string& source_name) {
  double total = 0, shared = 1;
  for (const Axis& a : spec.axes) shared *= double(a.size());
  for (const SpecPart& p : spec.parts) {
    double own = 1;
    for (const Axis& a : p.axes) own *= double(a.size());
    total += own * shared;
  }
  if (spec.parts.empty()) total = shared;
  if (total > max_runs) fail(source_name, "expands to " + fmt(total) + " runs (more than 1e12)");
}

SweepSpec parse_spec(const std::string& text, const std::string& source_name, const std::string& dir,
                     ExtendsChain& chain) {
  toml::table root = parse_toml(text, source_name);
  check_sections(root, source_name);
  SweepSpec spec;
  UsedKeys used;  // keys set outside parts, and where
  // Keys the extended spec's parts set: the top level must not set them too.
  UsedKeys inherited_part_keys;
  if (const toml::table* s = root["sweep"].as_table()) {
    check_sweep_keys(*s, source_name);
    if (auto n = (*s)["name"].value<std::string>()) spec.name = *n;
    if (auto d = (*s)["description"].value<std::string>()) spec.description = *d;
    if (auto e = (*s)["extends"].value<std::string>())
      extend_from(spec, parse_extended(*e, source_name, dir, chain), *e, root, source_name, used, inherited_part_keys);
  }
  spec.text += text;
  UsedKeys top = used;  // what the top level claims, checked against the inherited parts too
  top.insert(inherited_part_keys.begin(), inherited_part_keys.end());
  if (const toml::table* f = root["fixed"].as_table()) read_fixed(*f, source_name, spec, top);
  OrderedAxes ordered;
  parse_axis_sections(root, source_name + ": ", "", false, spec.base, top, ordered);
  if (const toml::table* t = root["repeat"].as_table()) read_repeat(*t, source_name, spec, top, ordered);
  for (Axis& a : in_file_order(std::move(ordered))) spec.axes.push_back(std::move(a));

  if (const toml::array* parts = root["part"].as_array()) {
    for (const auto& [key, use] : inherited_part_keys) top.erase(key);  // parts are independent of one another
    std::vector<std::string> names;
    for (const SpecPart& p : spec.parts) names.push_back(p.name);
    for (std::size_t k = 0; k < parts->size(); ++k) {
      spec.parts.push_back(parse_part(*parts->get(k)->as_table(), k, source_name, spec.base, top, names));
      names.push_back(spec.parts.back().name);
    }
  }
  check_run_count(spec, source_name);
  if (const toml::table* t = root["tune"].as_table()) {
    std::ostringstream tune;
    tune << *t;
    spec.tune = tune.str();
  }
  return spec;
}

}  // namespace

SweepSpec parse_sweep_spec(const std::string& text, const std::string& source_name, const std::string& dir) {
  ExtendsChain chain;
  return parse_spec(text, source_name, dir, chain);
}

SweepSpec load_sweep_spec(const std::string& path, const std::vector<SpecOverride>& overrides) {
  const auto slash = path.find_last_of('/');
  const std::string text = read_text(path, "the sweep spec");
  ExtendsChain chain{link_of(path)};
  SweepSpec s;
  try {
    s = parse_spec(apply_overrides(text, overrides, path), path,
                   slash == std::string::npos ? "." : path.substr(0, slash), chain);
  } catch (const SpecError& e) {
    if (overrides.empty() || std::string(e.what()).starts_with("--set ")) throw;
    std::string listed;
    for (const SpecOverride& o : overrides) listed += (listed.empty() ? "" : " ") + o.text();
    throw SpecError(std::string(e.what()) + " (the spec with --set " + listed + ")");
  }
  s.files.insert(s.files.begin(), InputRecord{recorded_path(path), fnv1a64(text)});
  if (s.name.empty()) {
    std::string stem = path.substr(slash == std::string::npos ? 0 : slash + 1);
    s.name = stem.substr(0, stem.rfind('.'));
  }
  return s;
}

}  // namespace chaosweep
