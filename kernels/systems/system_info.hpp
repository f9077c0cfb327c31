#pragma once
// What a run's parameters, the engine and the CLI ask of a listed system by
// its index, without the list itself (system_list.hpp, where these are
// defined): adding a system recompiles the kernels that step systems, not
// the layers above them.
#include <string_view>

#include "kernels/systems/system.hpp"

namespace chaosweep {

inline constexpr int arnold_system = 0;  // Arnold's place in the list (its coefficients are A, B, C)

// The name of the system of index s ("?" for an index out of range).
std::string_view system_name(int s);

// A system's defaults (the Arnold flow: no sys_* coefficients, its ic; an
// index out of range: all zero).
SystemDefaults system_defaults(int s);

}  // namespace chaosweep
