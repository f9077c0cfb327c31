#include "engine/spec/text_widths.hpp"

#include <algorithm>
#include <variant>

namespace chaosweep {

std::map<std::string, std::size_t> text_widths(const SweepSpec& spec) {
  // A number given as a label is printed (at most 24 characters).
  constexpr std::size_t number_text = 32;
  std::map<std::string, std::size_t> longest = {{"env", spec.base.env.size()}, {"label", spec.base.label.size()}};
  auto take = [&](const std::string& key, const SpecValue& v) {
    const auto it = longest.find(key);
    if (it == longest.end()) return;
    const std::size_t n = std::holds_alternative<std::string>(v) ? std::get<std::string>(v).size() : number_text;
    it->second = std::max(it->second, n);
  };
  auto settings = [&](const Settings& s) {
    for (const auto& [key, value] : s) take(key, value);
  };
  auto axes = [&](const std::vector<Axis>& list) {
    for (const Axis& a : list) {
      for (const Settings& s : a.values) settings(s);
      if (!a.sampler) continue;
      for (const Sampler::Dim& d : a.sampler->dims) {
        if (d.choices.empty()) take(d.key, 0.0);  // a range: numbers
        for (const SpecValue& c : d.choices) take(d.key, c);
      }
    }
  };
  axes(spec.axes);
  for (const SpecPart& part : spec.parts) {
    longest["label"] = std::max(longest["label"], part.name.size());  // a part's runs without a label
    settings(part.fixed);
    axes(part.axes);
  }
  for (auto& [key, n] : longest) n = (n + 1 + 7) / 8 * 8;
  return longest;
}

}  // namespace chaosweep
