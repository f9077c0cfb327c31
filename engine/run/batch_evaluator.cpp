#include "engine/run/batch_evaluator.hpp"

#include <stdexcept>

namespace chaosweep {

std::size_t BatchEvaluator::evaluate(std::span<const RunTuple> in, std::span<RunResult> out,
                                     const BatchObserver& observer) const {
  if (in.size() != out.size())
    throw std::invalid_argument("batch evaluator: " + std::to_string(in.size()) + " runs but " +
                                std::to_string(out.size()) + " result slots");
  for (const RunTuple& t : in)
    if (!t.env) throw std::invalid_argument("batch evaluator: run " + std::to_string(t.run_id) + " has no environment");
  const std::size_t done = run(in, out, observer);
  if (done > in.size()) throw std::logic_error("batch evaluator: more runs done than given");
  return done;
}

void BatchEvaluator::parallel(std::size_t n, const std::function<void(std::size_t)>& body) const {
  for (std::size_t i = 0; i < n; ++i) body(i);
}

RunResult BatchEvaluator::evaluate(const RunTuple& tuple) const {
  RunResult result;
  evaluate(std::span<const RunTuple>(&tuple, 1), std::span<RunResult>(&result, 1));
  return result;
}

}  // namespace chaosweep
