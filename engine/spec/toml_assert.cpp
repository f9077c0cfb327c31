#include "engine/spec/toml.hpp"

#include <cstdint>
#include <cstdio>

namespace chaosweep {

void toml_assert_failed(const char* expr) {
  throw TomlInputError(std::string("malformed TOML the parser cannot handle (") + expr + ")");
}

namespace {

// The code points toml++ 3.3.0's is_non_ascii_horizontal_whitespace sends to
// __builtin_unreachable: its lookup's first and last blocks fall through.
// Derived from its bit mask 0x7FFFFFFFFFFFF75E over blocks of 0x3FA from
// U+00A0: blocks 0, 11 and 63 have no case, except the three spaces it lists.
bool unsafe_code_point(unsigned cp) {
  return (cp >= 0xA1 && cp <= 0x499) || (cp >= 0x2C5E && cp <= 0x3057 && cp != 0x3000) ||
         (cp >= 0xFB26 && cp <= 0xFEFE);
}

// Walks `node`, `path` naming it as a spec's messages do ("axes.A.num",
// "zip[0].sr[2]").
void check_integers(const toml::node& node, const std::string& path) {
  constexpr std::int64_t exact = std::int64_t(1) << 53;
  if (const auto* i = node.as_integer()) {
    const std::int64_t v = i->get();
    if (v > exact || v < -exact)
      throw TomlInputError(path + " = " + std::to_string(v) +
                           " is too large: integers must lie within +-2^53 = +-9007199254740992, beyond which "
                           "they are not exact as numbers");
  } else if (const toml::table* t = node.as_table()) {
    for (auto&& [k, child] : *t)
      check_integers(child, path.empty() ? std::string(k.str()) : path + "." + std::string(k.str()));
  } else if (const toml::array* a = node.as_array()) {
    for (std::size_t j = 0; j < a->size(); ++j) check_integers(*a->get(j), path + "[" + std::to_string(j) + "]");
  }
}

}  // namespace

void check_toml_integers(const toml::table& root) { check_integers(root, ""); }

void check_toml_text(const std::string& text) {
  long line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto b0 = static_cast<unsigned char>(text[i]);
    if (b0 == '\n') ++line;
    unsigned cp = 0;
    std::size_t len = 0;
    auto cont = [&](std::size_t k) {
      return i + k < text.size() && (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80
                 ? static_cast<unsigned char>(text[i + k]) & 0x3Fu
                 : 0x100u;
    };
    if (b0 >= 0xC2 && b0 <= 0xDF && cont(1) < 0x100) {
      cp = ((b0 & 0x1Fu) << 6) | cont(1), len = 2;
    } else if (b0 >= 0xE0 && b0 <= 0xEF && cont(1) < 0x100 && cont(2) < 0x100) {
      cp = ((b0 & 0x0Fu) << 12) | (cont(1) << 6) | cont(2), len = 3;
    } else {
      continue;
    }
    if (unsafe_code_point(cp)) {
      char hex[16];
      std::snprintf(hex, sizeof hex, "U+%04X", cp);
      throw TomlInputError("line " + std::to_string(line) + ": the character " + hex +
                           " cannot be read safely by this TOML parser (toml++ 3.3.0: U+00A1..U+0499, "
                           "U+2C5E..U+3057, U+FB26..U+FEFE, anywhere in the file): use ASCII");
    }
    i += len - 1;
  }
}

}  // namespace chaosweep
