#pragma once
// What a result file records about where and when it was made (besides the
// version, engine/store/version.hpp).

#include <string>

namespace chaosweep {

std::string host_name();
std::string utc_now();  // ISO 8601

}  // namespace chaosweep
