#pragma once
// The Logistic map's orbit as MapZoning's transits draw it (seed 000, Eqs. 2
// and 4): each iterate, whether the orbit is still usable there, and the
// cosine and sine of the robot's heading on either branch; the later
// iterates shared by the runs of a sweep (core/shared_orbit.hpp). Transit
// points draw it from one x0 in every run (Table 1: no jitter), and their
// C-library sincos was an eighth of the Table 1 search (issue 20). The
// trigonometry stays the C library's: sincos.hpp's (the Logistic planner's,
// systems/logistic_map.hpp) differs in the last ulp, which moved transit
// paths across cell corners and changed 8 of Table 1's 97,760 coverage
// times, and its scalar form (a call per fma) was slower here than glibc's
// (BENCHMARKS.md, "The Logistic planner in the lanes").
#include "kernels/core/shared_orbit.hpp"

namespace chaosweep {

class LogisticOrbit {
 public:
  // x' = r x (1 - x) from x0.
  LogisticOrbit(double r, double x0);

  struct Heading {
    double x;  // the iterate
    bool ok;   // false: a degenerate orbit (a fixed point 0 or 1 - 1/r, or outside [0, 1]); the run ends diverged
    double cos, sin;  // of theta = pi x - pi/2 (rightwards) or pi x + pi/2
  };
  // The next iterate and the heading it gives on the branch asked for.
  Heading next(bool rightwards) {
    const Value* v = orbit_.take([this](double& x) { return both(x); });
    const Heading h = !v           ? draw(orbit_.state(), rightwards)
                      : rightwards ? Heading{v->x, v->ok, v->cos_right, v->sin_right}
                                   : Heading{v->x, v->ok, v->cos_left, v->sin_left};
    x_ = h.x;
    return h;
  }
  // n calls of next(rightwards), each heading passed to f(cos, sin), as far
  // as the first degenerate one (then false; it is not passed). Reads the
  // shared blocks a span at a time: next() per value kept the orbit's place
  // in memory from call to call (a transit's points, 6% of Table 1's search).
  template <class F>
  bool headings(long n, bool rightwards, F&& f) {
    while (n > 0) {
      const Value *first, *last;
      orbit_.take_span(n, first, last);
      if (first == last) {  // the run's own value, or a new block's first
        const Heading h = next(rightwards);
        if (!h.ok) return false;
        f(h.cos, h.sin);
        --n;
        continue;
      }
      for (const Value* v = first; v != last; ++v) {
        if (!v->ok) {
          orbit_.give_back(last - v - 1);
          x_ = v->x;
          return false;
        }
        if (rightwards) f(v->cos_right, v->sin_right);
        else f(v->cos_left, v->sin_left);
      }
      x_ = (last - 1)->x;
      n -= last - first;
    }
    return true;
  }
  // The last iterate drawn (x0 before the first).
  double x() const { return x_; }

  struct Value {  // a shared iterate: both branches
    double x;
    bool ok;
    double cos_right, sin_right, cos_left, sin_left;
  };

 private:
  // The iterate after x (x becomes it), with the heading on one branch, or both.
  Heading draw(double& x, bool rightwards) const;
  Value both(double& x) const;

  double r_, fixed_, x_;  // fixed_: LogisticMap::fixed_point(r_)
  SharedOrbit<Value> orbit_;
};

}  // namespace chaosweep
