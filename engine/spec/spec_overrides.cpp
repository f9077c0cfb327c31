#include "engine/spec/spec_overrides.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "engine/spec/sweep_spec.hpp"
#include "engine/spec/toml.hpp"

namespace chaosweep {

namespace {

[[noreturn]] void fail(const SpecOverride& o, const std::string& what) {
  throw SpecError("--set " + o.text() + ": " + what);
}

bool bare_word(const std::string& v) {
  return !v.empty() && std::all_of(v.begin(), v.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.' || c == '/' || c == '+';
  });
}

// VALUE as TOML text: itself when it parses as a value, a quoted string when
// it is a bare word, else the parser's complaint.
std::string toml_value(const SpecOverride& o, toml::node_type& type) {
  try {
    check_toml_text(o.value);
    const toml::table t = toml::parse("v = " + o.value);
    type = t["v"].type();
    return o.value;
  } catch (const std::exception& e) {
    if (!bare_word(o.value))
      fail(o,
           "the value is not a TOML value (a number, [list], { start = ..., stop = ..., num = ... } or "
           "\"text\"): " +
               std::string(e.what()));
  }
  type = toml::node_type::string;
  return "\"" + o.value + "\"";
}

// Byte offset of a toml++ position (1-based line and column in code points).
std::size_t offset_of(const std::string& text, const toml::source_position& p) {
  std::size_t i = 0;
  for (std::uint32_t line = 1; line < p.line && i < text.size(); ++i)
    if (text[i] == '\n') ++line;
  for (std::uint32_t col = 1; col < p.column && i < text.size(); ++col) {
    ++i;
    while (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) ++i;  // UTF-8 continuation
  }
  return i;
}

// One edit of the text: replace [begin, end) by `with`.
struct Edit {
  std::size_t begin, end;
  std::string with;
  std::size_t flag = 0;  // which --set, to keep their order where several insert at one place
};

// After the line of the table's last entry (or its header when empty).
std::size_t end_of_table(const std::string& text, const toml::table& t) {
  toml::source_position last = t.source().begin;
  for (auto&& [k, v] : t)
    if (v.source().end.line > last.line) last = v.source().end;
  const std::size_t at = text.find('\n', offset_of(text, {last.line, 1}));
  return at == std::string::npos ? text.size() : at + 1;
}

bool holds_key(const toml::node& n, const std::string& key) {
  if (const toml::table* t = n.as_table()) {
    for (auto&& [k, v] : *t)
      if (k.str() == key || holds_key(v, key)) return true;
  } else if (const toml::array* a = n.as_array()) {
    for (const toml::node& e : *a)
      if (holds_key(e, key)) return true;
  }
  return false;
}

// The section other than [fixed] and [axes] that sets `key`, if any.
std::string where_else(const toml::table& root, const std::string& key) {
  for (const char* section : {"zip", "case", "part"})
    if (const toml::node* n = root.get(section); n && holds_key(*n, key)) return std::string("[[") + section + "]]";
  if (const toml::node* n = root.get("sample"); n && holds_key(*n, key)) return "[sample]";
  return "";
}

void plan_edit(const std::string& text, const toml::table& root, const SpecOverride& o, std::vector<Edit>& edits,
               std::string& appended) {
  std::string section, key = o.key;
  if (const auto dot = key.find('.'); dot != std::string::npos) {
    section = key.substr(0, dot);
    key = key.substr(dot + 1);
    if (section != "fixed" && section != "axes" && section != "sweep")
      fail(o, "the key must be KEY, fixed.KEY, axes.KEY, sweep.name or sweep.description");
    if (section == "sweep" && key != "name" && key != "description")
      fail(o, "of [sweep], only name and description can be set from the command line");
  }
  if (key.empty() || !bare_word(key) || key.find('.') != std::string::npos)
    fail(o, "'" + o.key + "' is not a key of the spec");
  if (const std::string other = where_else(root, key); !other.empty() && section != "sweep")
    fail(o, "'" + key + "' is set by the spec's " + other +
                ": --set changes the spec file's [fixed] settings and [axes] only");
  toml::node_type type{};
  std::string value = toml_value(o, type);
  const bool many = type == toml::node_type::array || type == toml::node_type::table;
  if (section.empty()) section = root["axes"][key] ? "axes" : "fixed";
  // A list of numbers for a tuple setting (start = [x, y]) stays a fixed value;
  // any other list or range sweeps the key.
  const bool tuple = type == toml::node_type::array && (key == "start" || key == "ic");
  if (section == "fixed" && many && !tuple && o.key.rfind("fixed.", 0) != 0) section = "axes";
  if (section == "axes" && !many) value = "[" + value + "]";  // one position: run ids keep their meaning

  // Replace the value where the key is written, or drop it from the other section.
  for (const char* s : {"sweep", "fixed", "axes"}) {
    const toml::table* t = root[s].as_table();
    if (!t) continue;
    for (auto&& [k, v] : *t) {
      if (k.str() != key) continue;
      if (section == s) {
        edits.push_back({offset_of(text, v.source().begin), offset_of(text, v.source().end), value});
        return;
      }
      edits.push_back({offset_of(text, k.source().begin), offset_of(text, v.source().end), ""});
    }
  }
  const std::string line = key + " = " + value + "\n";
  if (const toml::table* t = root[section].as_table()) {
    const std::size_t at = end_of_table(text, *t);
    edits.push_back({at, at, line});
  } else {
    appended += "\n[" + section + "]\n" + line;
  }
}

}  // namespace

SpecOverride parse_override(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SpecError("--set " + arg + ": must be KEY=VALUE (e.g. --set sr=4, --set A=[0.4,0.5])");
  SpecOverride o{arg.substr(0, eq), arg.substr(eq + 1)};
  auto trim = [](std::string& s) {
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
  };
  trim(o.key);
  trim(o.value);
  if (o.value.empty()) throw SpecError("--set " + arg + ": the value is empty");
  if (o.value.find('\n') != std::string::npos) throw SpecError("--set " + o.key + ": the value spans lines");
  return o;
}

std::string apply_overrides(const std::string& text, const std::vector<SpecOverride>& overrides,
                            const std::string& source_name) {
  if (overrides.empty()) return text;
  toml::table root;
  try {
    check_toml_text(text);
    root = toml::parse(text, source_name);
  } catch (const std::exception&) {
    return text;  // the spec's own parse names the problem
  }
  std::vector<Edit> edits;
  std::string appended, listed;
  std::set<std::string> keys;
  for (const SpecOverride& o : overrides) {
    const std::size_t first = edits.size();
    const std::string bare = o.key.substr(o.key.find('.') + 1);  // npos + 1 == 0: the whole key
    if (!keys.insert(bare).second) fail(o, "'" + bare + "' is given twice");
    plan_edit(text, root, o, edits, appended);
    for (std::size_t k = first; k < edits.size(); ++k) edits[k].flag = keys.size();
    listed += " " + o.text();
  }
  // Apply from the end, so earlier offsets stay valid; of insertions at one
  // place the last flag goes first, so they read in the flags' order.
  std::sort(edits.begin(), edits.end(),
            [](const Edit& a, const Edit& b) { return a.begin != b.begin ? a.begin > b.begin : a.flag > b.flag; });
  std::string out = text;
  for (const Edit& e : edits) out.replace(e.begin, e.end - e.begin, e.with);
  if (!out.empty() && out.back() != '\n') out += '\n';
  // The note goes last, so that line numbers in messages stay the file's.
  return out + appended + "# chaosweep --set" + listed + "\n";
}

}  // namespace chaosweep
