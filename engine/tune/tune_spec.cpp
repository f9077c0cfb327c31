#include "engine/tune/tune_spec.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "engine/spec/toml.hpp"

namespace chaosweep {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw SpecError(where + ": " + what); }

toml::table parse_tune_table(const std::string& text, const std::string& where) {
  try {
    check_toml_text(text);
    return toml::parse(text, where);
  } catch (const toml::parse_error& e) {
    fail(where, std::string(e.description()));
  }
}

SpecValue value_of(const toml::node& n, const std::string& where) {
  if (n.is_integer() || n.is_floating_point()) return *n.value<double>();
  if (n.is_string()) return *n.value<std::string>();
  fail(where, "must be a number or a string");
}

double number(const toml::node& n, const std::string& where, double lo, double hi, bool whole) {
  const auto v = n.value<double>();
  if (!v || !(*v >= lo && *v <= hi) || (whole && *v != std::floor(*v))) {
    std::ostringstream os;
    os << "must be " << (whole ? "a whole number" : "a number") << " in [" << lo << ", " << hi << "]";
    fail(where, os.str());
  }
  return *v;
}

// The value is one the parameter can take (apply_setting's own check).
void check_setting(const std::string& key, const SpecValue& v, const std::string& where) {
  RunSpec scratch;
  try {
    apply_setting(scratch, key, v);
  } catch (const SpecError& e) {
    fail(where, e.what());
  }
}

TuneParameter parse_parameter(const std::string& key, const toml::node& n, const std::string& where) {
  if (key == "seed") fail(where, "the tuner sets each run's seed; 'seed' cannot be searched");
  if (key == "env" || key == "label" || key == "size" || key == "start" || key == "ic")
    fail(where, "only a run parameter can be searched (not " + key + ")");
  TuneParameter p;
  p.key = key;
  if (const toml::table* t = n.as_table()) {
    for (auto&& [k, v] : *t)
      if (k.str() != "min" && k.str() != "max")
        fail(where, "unknown key '" + std::string(k.str()) + "' (a range is { min = ..., max = ... })");
    if (!(*t)["min"] || !(*t)["max"]) fail(where, "a range needs both min and max");
    p.real = true;
    p.lo = number(*t->get("min"), where + ".min", -1e300, 1e300, false);
    p.hi = number(*t->get("max"), where + ".max", -1e300, 1e300, false);
    if (!(p.lo < p.hi)) fail(where, "min must be below max");
    check_setting(key, p.lo, where + ".min");
    check_setting(key, p.hi, where + ".max");
  } else if (const toml::array* a = n.as_array()) {
    if (a->empty()) fail(where, "a list of values must not be empty");
    for (std::size_t i = 0; i < a->size(); ++i) {
      const std::string at = where + "[" + std::to_string(i) + "]";
      SpecValue v = value_of(*a->get(i), at);
      check_setting(key, v, at);
      for (const SpecValue& w : p.choices)
        if (w == v) fail(at, "is listed twice");
      p.choices.push_back(std::move(v));
    }
  } else {
    fail(where, "must be a range { min = ..., max = ... } or a list of values");
  }
  return p;
}

// Keys the spec's axes (top level or a part's) or a part's fixed settings
// set: the tuner would overwrite them, so they cannot be searched too.
std::set<std::string> spec_set_keys(const SweepSpec& spec) {
  std::set<std::string> keys;
  for (const Axis& a : spec.axes) keys.insert(a.keys.begin(), a.keys.end());
  for (const SpecPart& p : spec.parts) {
    for (const Axis& a : p.axes) keys.insert(a.keys.begin(), a.keys.end());
    for (const auto& [k, v] : p.fixed) keys.insert(k);
  }
  return keys;
}

std::size_t index_of(const TuneSpec& t, const std::string& key) {
  for (std::size_t i = 0; i < t.parameters.size(); ++i)
    if (t.parameters[i].key == key) return i;
  return t.parameters.size();
}

struct PartTune {
  std::vector<std::size_t> parameters;
  std::optional<std::int64_t> budget;
};

PartTune parse_part_tune(const TuneSpec& t, const toml::node& n, const std::string& where) {
  const toml::table* tab = n.as_table();
  if (!tab) fail(where, "must be a table { parameters = [...], budget = N }");
  PartTune out;
  for (auto&& [k, v] : *tab) {
    const std::string key(k.str());
    if (key == "budget") {
      out.budget = std::int64_t(number(v, where + ".budget", 1, 1e9, true));
    } else if (key == "parameters") {
      const toml::array* a = v.as_array();
      if (!a) fail(where + ".parameters", "must be a list of names from tune.parameters");
      for (std::size_t i = 0; i < a->size(); ++i) {
        const std::string at = where + ".parameters[" + std::to_string(i) + "]";
        const auto name = a->get(i)->value<std::string>();
        if (!name) fail(at, "must be a name from tune.parameters");
        const std::size_t j = index_of(t, *name);
        if (j == t.parameters.size()) fail(at, "'" + *name + "' is not in tune.parameters");
        for (std::size_t q : out.parameters)
          if (q == j) fail(at, "'" + *name + "' is listed twice");
        out.parameters.push_back(j);
      }
    } else {
      fail(where, "unknown key '" + key + "' (allowed: parameters, budget)");
    }
  }
  return out;
}

}  // namespace

const char* to_string(RaceTest t) { return t == RaceTest::friedman ? "friedman" : "wilcoxon"; }

std::int64_t minimum_budget(const TuneSpec& tune) { return 2 * std::int64_t(tune.first_test); }

TuneSpec tune_spec_of(const SweepSpec& spec, const std::string& source_name, std::optional<std::int64_t> budget) {
  const std::string where = source_name + ": tune";
  if (spec.tune.empty()) fail(source_name, "has no [tune] section (what to search, the budget): see docs/tune.md");
  const toml::table root = parse_tune_table(spec.tune, where);
  if (spec.repeat || spec_set_keys(spec).count("seed"))
    fail(source_name, "sets the runs' seed ([repeat] or a seed axis): the tuner sets each run's seed itself");
  TuneSpec t;
  std::optional<std::int64_t> default_budget;
  const toml::table* parts = nullptr;
  for (auto&& [k, v] : root) {
    const std::string key(k.str());
    const std::string at = where + "." + key;
    if (key == "parameters") {
      const toml::table* ps = v.as_table();
      if (!ps || ps->empty())
        fail(at, "must be a table of the parameters to search (e.g. c = { min = 0.05, max = 1 })");
      const std::set<std::string> taken = spec_set_keys(spec);
      for (auto&& [pk, pv] : *ps) {
        const std::string name(pk.str());
        if (taken.count(name)) fail(at + "." + name, "is set by the spec's axes or a part; it cannot be searched too");
        t.parameters.push_back(parse_parameter(name, pv, at + "." + name));
      }
    } else if (key == "part") {
      parts = v.as_table();
      if (!parts) fail(at, "must be a table of parts ([tune.part.NAME])");
    } else if (key == "budget") {
      default_budget = std::int64_t(number(v, at, 1, 1e9, true));
    } else if (key == "seed") {
      t.seed = std::uint64_t(number(v, at, 0, 9007199254740991.0, true));
    } else if (key == "confidence") {
      t.confidence = number(v, at, 0.5, 0.999, false);
    } else if (key == "test") {
      const auto s = v.value<std::string>();
      if (!s || (*s != "friedman" && *s != "wilcoxon")) fail(at, "must be \"friedman\" or \"wilcoxon\"");
      t.test = *s == "friedman" ? RaceTest::friedman : RaceTest::wilcoxon;
    } else if (key == "first_test") {
      t.first_test = int(number(v, at, 2, 1000, true));
    } else if (key == "each_test") {
      t.each_test = int(number(v, at, 1, 1000, true));
    } else if (key == "post_selection") {
      t.post_selection = number(v, at, 0, 0.9, false);
    } else if (key == "digits") {
      t.digits = int(number(v, at, 1, 15, true));
    } else if (key == "validation_seeds") {
      t.validation_seeds = int(number(v, at, 0, 100000, true));
    } else if (key == "validation_first_seed") {
      t.validation_first_seed = std::int64_t(number(v, at, 0, 9e15, true));
    } else {
      fail(where, "unknown key '" + key +
                      "' (allowed: parameters, part, budget, seed, confidence, test, first_test, each_test, "
                      "post_selection, digits, validation_seeds, validation_first_seed)");
    }
  }
  if (t.parameters.empty()) fail(where + ".parameters", "is missing: name the parameters to search");
  if (budget) default_budget = budget;
  // Which parameters each part searches (all, without [tune.part]).
  std::vector<PartTune> per_part(std::max<std::size_t>(spec.parts.size(), 1));
  for (PartTune& p : per_part)
    for (std::size_t j = 0; j < t.parameters.size(); ++j) p.parameters.push_back(j);
  if (parts) {
    if (spec.parts.empty()) fail(where + ".part", "the spec has no [[part]]s");
    for (auto&& [pk, pv] : *parts) {
      const std::string name(pk.str());
      std::size_t k = 0;
      while (k < spec.parts.size() && spec.parts[k].name != name) ++k;
      if (k == spec.parts.size()) fail(where + ".part." + name, "is not a [[part]] of the spec");
      per_part[k] = parse_part_tune(t, pv, where + ".part." + name);
    }
    for (std::size_t k = 0; k < spec.parts.size(); ++k)
      if (!parts->contains(spec.parts[k].name))
        fail(where + ".part", "has no entry for part '" + spec.parts[k].name +
                                  "': list every part (parameters = [] to only validate its one configuration)");
  }
  if (spec.size() > 100000) fail(source_name, "has " + std::to_string(spec.size()) + " cases (at most 100000)");
  for (std::int64_t i = 0; i < spec.size(); ++i) {
    TuneCase c;
    c.run = spec.run(i);
    const std::size_t k = spec.parts.empty() ? 0 : spec.part_of(i);
    if (!spec.parts.empty()) c.part = spec.parts[k].name;
    c.parameters = per_part[k].parameters;
    const auto b = budget ? budget : per_part[k].budget ? per_part[k].budget : default_budget;
    if (!c.parameters.empty()) {
      const std::string named =
          per_part[k].budget && !budget ? where + ".part." + c.part + ".budget" : where + ".budget";
      if (!b) fail(named, "is missing: give the race runs each case may spend");
      if (*b < minimum_budget(t))
        fail(budget ? std::string("--budget") : named,
             "must be at least " + std::to_string(minimum_budget(t)) + " (first_test seeds of two configurations)");
      c.budget = *b;
    }
    t.cases.push_back(std::move(c));
  }
  return t;
}

RunSpec tune_run(const TuneSpec& tune, const TuneCase& c, const std::vector<double>& values, std::int64_t seed) {
  RunSpec r = c.run;
  for (std::size_t i = 0; i < c.parameters.size(); ++i) {
    const TuneParameter& p = tune.parameters[c.parameters[i]];
    if (p.real) apply_setting(r, p.key, values[i]);
    else apply_setting(r, p.key, p.choices[std::size_t(values[i])]);
  }
  apply_setting(r, "seed", double(seed));
  return r;
}

}  // namespace chaosweep
