#pragma once
// toml++ (Debian 3.3.0) as every engine file must include it. Its parser
// checks some preconditions with TOML_ASSERT_ASSUME, which with NDEBUG
// becomes an optimiser assumption: malformed input such as "[\x15" or
// "[[[1]]]" then has undefined behaviour (found by tests/fuzz; fixed upstream
// in toml++ PR #301). Here the checks stay on in every build and throw, so bad
// input is reported, never undefined. All TUs use this header, so toml++'s
// inline code is compiled one way (ODR).
#include <stdexcept>
#include <string>

namespace chaosweep {
struct TomlInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Throws TomlInputError (defined out of line, so that toml++'s few noexcept
// accessors compile without warnings; a failure there would terminate, as an
// assert would).
[[noreturn]] void toml_assert_failed(const char* expr);

// Call before toml::parse. toml++ 3.3.0 also reaches __builtin_unreachable
// when it tests a code point in U+00A1..U+0499 for whitespace (found by
// tests/fuzz, in malformed documents where string boundaries are anyone's
// guess): such code points are refused anywhere in the file, naming the line
// (other UTF-8, e.g. the em dash, is fine).
void check_toml_text(const std::string& text);
}  // namespace chaosweep

#ifdef NDEBUG
#define CHAOSWEEP_TOML_NDEBUG
#undef NDEBUG
#endif
#define TOML_ASSERT(expr)                                \
  do {                                                   \
    if (!(expr)) ::chaosweep::toml_assert_failed(#expr); \
  } while (0)
#include <toml++/toml.h>
#ifdef CHAOSWEEP_TOML_NDEBUG
#define NDEBUG
#undef CHAOSWEEP_TOML_NDEBUG
#endif

namespace chaosweep {
// Call after toml::parse. toml++ keeps an integer as int64, and its
// value<double>() is empty for one beyond +-2^53 (not exact as a double);
// reading that as a number read garbage ("num = 9223372036854775807 ...
// not 4.67053e-310"). Such integers are refused anywhere in the document:
// throws TomlInputError naming the key ("axes.A.num = ... is too large").
void check_toml_integers(const toml::table& root);
}  // namespace chaosweep
