#pragma once
// A Chebyshev map's orbit as the planner draws it (Eq. 1, then the transform
// of Eqs. 4-5 scaled to [0, 1]), its later iterates shared by the runs of a
// sweep (core/shared_orbit.hpp): two runs with the same order, initial value
// and transform draw the same values (the Y map's initial value is usually
// fixed, the X map's an axis), and cos(k arccos x) and the transform's
// arcsine were a quarter of the planner's time (issue 20).
#include "kernels/core/shared_orbit.hpp"
#include "kernels/systems/cheb_transform.hpp"

namespace chaosweep {

class ChebyshevOrbit {
 public:
  struct Value {
    double x;  // the map's iterate x_n
    double u;  // its transformed value, (T(x_n) - lo) / (hi - lo) in [0, 1]
  };

  ChebyshevOrbit(int k, double x0, ChebTransform transform);

  // x_1, x_2, ... in turn.
  Value next() {
    if (const Value* v = orbit_.take([this](double& x) { return draw(x); })) return *v;
    return draw(orbit_.state());
  }

 private:
  Value draw(double& x) const;  // the iterate after x, and x becomes it

  int k_;
  ChebTransform transform_;
  SharedOrbit<Value> orbit_;
};

}  // namespace chaosweep
