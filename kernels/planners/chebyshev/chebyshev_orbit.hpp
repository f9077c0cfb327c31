#pragma once
// A Chebyshev map's orbit as the planner draws it (Eq. 1, then the transform
// of Eqs. 4-5 scaled to [0, 1]), its later iterates in blocks that the runs
// of a sweep share: two runs with the same order, initial value and
// transform draw the same values (the Y map's initial value is usually
// fixed, the X map's an axis), and cos(k arccos x) and the transform's
// arcsine were a quarter of the planner's time (issue 20). A block is a pure
// function of its key, so sharing never shows in a result. A block is built
// when a second run reaches it (the first leaves a mark and draws on): an
// orbit that no other run draws costs a mark per block, never iterates that
// no one reads.
#include <memory>

#include "kernels/systems/cheb_transform.hpp"

namespace chaosweep {

struct OrbitBlock;

class ChebyshevOrbit {
 public:
  ChebyshevOrbit(int k, double x0, ChebTransform transform);
  ~ChebyshevOrbit();

  struct Value {
    double x;  // the map's iterate x_n
    double u;  // its transformed value, (T(x_n) - lo) / (hi - lo) in [0, 1]
  };
  // x_1, x_2, ... in turn.
  Value next() { return at_ != end_ ? *at_++ : advance(); }

  // The first iterates a run computes itself, one at a time as it draws
  // them: a run that stops after a few sub-goals (a sweep of many short
  // runs, each from its own x0) then costs no block and no cache lookup.
  static constexpr int own_iterates = 32;

 private:
  Value advance();

  int k_;
  double x0_;
  ChebTransform transform_;
  double x_;                     // the last iterate the run drew itself
  long drawn_ = 0;               // iterates drawn (a block's all at once, when taken)
  long own_end_ = own_iterates;  // the run draws its own iterates up to here
  int index_ = -1;               // the last block looked up
  std::shared_ptr<const OrbitBlock> block_;
  const Value* at_ = nullptr;
  const Value* end_ = nullptr;
};

}  // namespace chaosweep
