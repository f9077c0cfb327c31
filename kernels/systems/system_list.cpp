#include "kernels/systems/system_list.hpp"

namespace chaosweep {

std::string_view system_name(int s) {
  std::string_view n = "?";
  with_system(s, [&](auto tag) { n = decltype(tag)::type::name; });
  return n;
}

SystemDefaults system_defaults(int s) {
  SystemDefaults d{0, 0, 0, 0, 0, {"", "", "", ""}, {0, 0, 0}};
  with_system(s, [&](auto tag) { d = decltype(tag)::type::defaults; });
  return d;
}

}  // namespace chaosweep
