#include "kernels/core/param_table.hpp"
#include "kernels/core/trace.hpp"
#include "kernels/systems/system_list.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace chaosweep {

namespace {

using Kind = ParamInfo::Kind;

// A double for an integer field, saturating (NaN as 0). check() refuses such
// values before a run uses them, but set() also takes unchecked ones (a
// stored row before its check, the hash tests), and converting 1e300 or NaN
// to an integer is undefined behaviour.
template <class T>
T saturating(double v) {
  constexpr double lo = double(std::numeric_limits<T>::min()), hi = double(std::numeric_limits<T>::max());
  if (std::isnan(v)) return T(0);
  if (v <= lo) return std::numeric_limits<T>::min();
  if (v >= hi) return std::numeric_limits<T>::max();
  return T(v);
}

#define CW_REAL(field, lo, hi, unset_ok, help)                                                               \
  ParamInfo {                                                                                                \
#field, help, Kind::real, lo, hi, unset_ok,                                                              \
        {}, [](const RunParams& p) { return double(p.field); }, [](RunParams & p, double v) { p.field = v; } \
  }
#define CW_INT(field, lo, hi, help)                                                                                    \
  ParamInfo {                                                                                                          \
#field, help, Kind::integer, lo, hi, false,                                                                        \
        {},                                                                                                            \
         [](const RunParams& p) { return double(p.field); },                                                           \
                                                          [](RunParams & p,                                            \
                                                             double v) { p.field = saturating<decltype(p.field)>(v); } \
  }
#define CW_CHOICE(field, type, help, ...)                                                                              \
  ParamInfo {                                                                                                          \
#field, help, Kind::choice, 0, 0, false,                                                                           \
        {__VA_ARGS__ },                                                                                                \
         [](const RunParams& p) { return double(int(p.field)); }, [](RunParams & p,                                    \
                                                                     double v) { p.field = type(saturating<int>(v)); } \
  }

// A parameter added after result files began to store param_hash (see
// ParamInfo::hashed_at_default).
ParamInfo added_later(ParamInfo info) {
  info.hashed_at_default = false;
  return info;
}

// `system`: a choice whose names are system_list.hpp's.
ParamInfo system_param() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> n;
    for (int s = 0; s < system_count; ++s) n.push_back(system_name(s));
    return n;
  }();
  return added_later(ParamInfo{"system",
                               "chaotic system driving the Arnold planner family (planner = arnold): the Arnold "
                               "flow, or a flow (kernels/systems/flows/) or map (maps/) with coefficients sys_a..sys_d",
                               Kind::choice, 0, 0, false, names, [](const RunParams& p) { return double(p.system); },
                               [](RunParams& p, double v) { p.system = saturating<int>(v); }});
}

// ic_x, ic_y, ic_z: read as the initial state the run takes (system_ic: an
// unset one is its system's default), so rows, hashes and `run --from` see
// the value used, and an Arnold run's as before they could be unset.
template <int K>
ParamInfo ic_param() {
  static constexpr const char* names[] = {"ic_x", "ic_y", "ic_z"};
  static constexpr const char* helps[] = {
      "initial state x of the chaotic system (unset: the system's default, Arnold 0)",
      "initial state y of the chaotic system (unset: the system's default, Arnold 1)",
      "initial state z of the chaotic system (unset: the system's default, Arnold 0)"};
  return ParamInfo{names[K],
                   helps[K],
                   Kind::real,
                   -1e6,
                   1e6,
                   false,
                   {},
                   [](const RunParams& p) {
                     const Vec3<double> u = system_ic(p);
                     return K == 0 ? u.x : K == 1 ? u.y : u.z;
                   },
                   [](RunParams& p, double v) {
                     (K == 0 ? p.ic_x : K == 1 ? p.ic_y : p.ic_z) = v;
                   }};
}

// sys_a..sys_d's help: what the coefficient is in each flow that uses it.
std::string_view coeff_help(int i) {
  static const std::vector<std::string> texts = [] {
    std::vector<std::string> t;
    for (int k = 0; k < 4; ++k) {
      std::string s = "system coefficient ";
      s.push_back(char('a' + k));
      s.append(" (unset: the system's default):");
      const char* sep = " ";
      for_each_system([&](auto tag) {
        using F = typename decltype(tag)::type;
        if constexpr (F::defaults.count == 0) return;  // the Arnold flow's are A, B, C
        if (k >= F::defaults.count) return;
        s.append(sep).append(F::name).append(" ").append(F::defaults.names[k]).append(" = ");
        s.append(format_number(F::defaults.coeffs().at(k)));
        sep = ", ";
      });
      t.push_back(s);
    }
    return t;
  }();
  return texts[std::size_t(i)];
}

std::vector<ParamInfo> make_table() {
  std::vector<ParamInfo> t = {
      CW_CHOICE(planner, Planner,
                "planner: Arnold flow (with the switches below), Logistic map only, Chebyshev map (seed 001), "
                "Arnold contraction (seed 003), bouncing robot (seed 002), or a baseline: random walk, random "
                "bounce, boustrophedon lawnmower",
                "arnold", "logistic", "chebyshev", "contraction", "bouncing", "random_walk", "random_bounce",
                "lawnmower"),
      system_param(),
      added_later(CW_REAL(sys_a, -1e6, 1e6, true, coeff_help(0))),
      added_later(CW_REAL(sys_b, -1e6, 1e6, true, coeff_help(1))),
      added_later(CW_REAL(sys_c, -1e6, 1e6, true, coeff_help(2))),
      added_later(CW_REAL(sys_d, -1e6, 1e6, true, coeff_help(3))),
      CW_INT(index_switching, 0, 1, "orientation control: 1 switches DSindex when coverage stalls"),
      CW_INT(switch_min_new, 0, 1e9, "a segment adding at most this many cells counts as stalled"),
      CW_INT(map_zoning, 0, 1, "map zoning: 1 runs MapZoning when Eq. 5 fails"),
      CW_REAL(c, 0, 1e3, false, "Eq. 5 coefficient c"),
      CW_INT(zones_x, 1, 1000, "MapZoning zones along X"),
      CW_INT(zones_y, 1, 1000, "MapZoning zones along Y"),
      CW_CHOICE(zone_goal, ZoneGoal,
                "transit goal: the zone midpoint, or (free) the nearest free cell when the midpoint "
                "is within fo of an obstacle",
                "free", "midpoint"),
      CW_CHOICE(zone_order, ZoneOrder,
                "MapZoning's zone ranking: auto (lowest density first on open maps, nearest first with "
                "obstacles), or always density or distance first (ties by the other)",
                "auto", "density", "distance"),
      CW_INT(th, 0, 1e9, "transit attempts per zone (0: 10 * L / 50)"),
      CW_INT(dnh, 0, 1e9, "th grows by dnh when every zone failed"),
      CW_REAL(dt_c, 1e-6, 10, false, "transit / Logistic step, s"),
      CW_CHOICE(transit_time, TransitTime,
                "robot time of a transit point: dt_c each (Algorithm 4), or its distance from the previous "
                "point at speed v",
                "points", "distance"),
      CW_CHOICE(transit_replan, TransitReplan,
                "transit re-plan at an obstacle (Algorithm 4): a fresh Logistic path from the pushed-out point, "
                "or the remaining Logistic points mapped anew from it",
                "fresh", "reuse"),
      CW_REAL(logistic_r, 0, 4, false, "Logistic map parameter r"),
      CW_REAL(logistic_x0, 0, 1, false, "Logistic map initial state"),
      CW_CHOICE(logistic_reset, LogisticReset,
                "the transits' Logistic state: carried on (never reset), or reset to its initial value when a "
                "zone is dropped (Algorithm 2, line 36)",
                "never", "drop"),
      CW_INT(cheb_k, 2, 1000, "Chebyshev map order k"),
      CW_REAL(cheb_x0, -1, 1, false, "Chebyshev map initial value of the X map"),
      CW_REAL(cheb_y0, -1, 1, false, "Chebyshev map initial value of the Y map"),
      CW_CHOICE(cheb_transform, ChebTransform, "transform of the Chebyshev orbit before mapping (Eqs. 4-5)", "none",
                "arcsine", "arccosine"),
      CW_REAL(radius, 0, 1e3, false, "Chebyshev robot radius, m (edge expansion)"),
      CW_REAL(step, 1e-4, 1e3, false,
              "robot step, m (Chebyshev, lawnmower: between interpolated points; bouncing, random_bounce, "
              "random_walk: per move)"),
      CW_INT(loop_subgoals, 1, 1e9, "Chebyshev sub-goals per large loop (split over the rectangles by area)"),
      CW_INT(max_subgoals, 0, 9.007199254740992e15, "end a Chebyshev run after this many sub-goals (0: no limit)"),
      CW_CHOICE(c3_mode, ContractionMode,
                "contraction planner: one Map-compressed trajectory, the complete-coverage loop, or mirror mapping",
                "map", "loop", "mirror"),
      CW_INT(c3_n, 1, 1e8, "contraction planner: RK2 steps of the trajectory (map, mirror)"),
      CW_REAL(c3_ic_grid, 0.05, 10, false, "contraction loop: step of the Arnold initial-state grid of candidates"),
      CW_REAL(bounce_phi1, 0, 360, false, "bouncing robot: policy 1's turn at a bump, degrees counter-clockwise"),
      CW_REAL(bounce_phi2, 0, 360, false, "bouncing robot: policy 2's turn, degrees"),
      CW_REAL(bounce_phi3, 0, 360, false, "bouncing robot: policy 3's turn, degrees"),
      CW_REAL(bounce_alpha1, 0, 1, false, "bouncing robot: weight of policy 1 in the mixture"),
      CW_REAL(bounce_alpha2, 0, 1, false, "bouncing robot: weight of policy 2"),
      CW_REAL(bounce_alpha3, 0, 1, false, "bouncing robot: weight of policy 3"),
      CW_REAL(bounce_eps, 0, 180, false, "bouncing robot: rotation error bound eps, degrees"),
      CW_REAL(bounce_r, 0, 1, false, "bouncing robot: probability the rotation is exact"),
      CW_REAL(bounce_heading, -360, 360, false, "bouncing robot: initial heading, degrees"),
      CW_REAL(ic_jitter, 0, 1, false, "perturb ic uniformly in +-ic_jitter (seeded by seed)"),
      CW_REAL(logistic_jitter, 0, 0.5, false,
              "perturb logistic_x0 uniformly in +-logistic_jitter (seeded by seed, independently of ic)"),
      CW_REAL(A, -1e3, 1e3, false, "Arnold coefficient A"),
      CW_REAL(B, -1e3, 1e3, false, "Arnold coefficient B"),
      CW_REAL(C, -1e3, 1e3, false, "Arnold coefficient C"),
      ic_param<0>(),
      ic_param<1>(),
      ic_param<2>(),
      CW_INT(ds_index, 1, 3, "Arnold coordinate driving the heading: 1=x, 2=y, 3=z"),
      CW_REAL(f, 1e-3, 1e3, false, "scaling factor f (1 = no scaling)"),
      CW_REAL(v, 1e-3, 1e3, false, "robot speed, m/s"),
      CW_REAL(dt, 1e-6, 10, false, "integration step, s"),
      CW_REAL(ep, 1e-15, 1, false, "step-doubling tolerance, m"),
      CW_REAL(dt_min, 0, 10, false, "smallest step doubling may reach before the run is diverged, s"),
      CW_REAL(fo, 0, 1e3, false, "boundary/obstacle offset fo, m"),
      CW_REAL(size_x, 1e-3, 1e6, false, "map side along X, m"),
      CW_REAL(size_y, 1e-3, 1e6, false, "map side along Y, m"),
      CW_REAL(sr, 1e-3, 1e4, false, "sensing range = coverage cell side, m"),
      CW_REAL(start_x, -1e9, 1e9, true, "start X, m (unset: the environment's start)"),
      CW_REAL(start_y, -1e9, 1e9, true, "start Y, m (unset: the environment's start)"),
      CW_CHOICE(boundary, Boundary, "wall handling: Eq. 7 mirror or unfolded-plane fold", "mirror", "fold"),
      CW_CHOICE(obstacle_response, ObstacleResponse,
                "obstacle faces (Eq. 8): push the point onto the face + fo, mirror it about that line, or "
                "mirror it and reverse the motion along that axis (a bounce)",
                "push", "mirror", "reflect"),
      CW_CHOICE(integrator, Integrator, "fixed-step RK4 or RK4 with step doubling", "rk4", "rk4-doubling"),
      CW_CHOICE(sampling, Sampling, "cells visited: by the segment between samples, or by the samples only", "segments",
                "points"),
      CW_CHOICE(coverage_cells, CoverageCells,
                "what coverage counts: visited free cells of the free cells, or (all) visited free cells plus "
                "obstacle cells of all cells (Eq. 5's c_T = all cells)",
                "free", "all"),
      CW_REAL(dc, 1e-6, 1, false, "desired coverage, fraction of free cells (coverage_cells = all: of all cells)"),
      CW_REAL(max_time, 0, 1e10, false, "robot-time budget, s (0: max_pr * T_opt)"),
      CW_REAL(max_pr, 1e-3, 1e6, false, "budget in multiples of T_opt when max_time = 0"),
      CW_REAL(stuck_time, 0, 1e10, false, "end as stuck after this long without a new cell, s (0: never)"),
      CW_INT(niter, 1, 1e9, "points per segment (SystemScaler call)"),
      CW_INT(seed, 0, 9.007199254740992e15, "seed of the run's random draws (ic_jitter, logistic_jitter)"),
  };
  return t;
}

}  // namespace

std::string format_number(double v, int significant) {
  char buf[32];
  if (significant > 0) {  // as printf("%.*g"), which spells nan and inf with their sign
    const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, significant);
    return std::string(buf, res.ptr);
  }
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // the shortest text that reads back to the same double
  return std::string(buf, res.ptr);
}

std::string ParamInfo::range_text() const {
  if (kind == Kind::choice) {
    std::string s = "one of";
    for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : " ") + std::string(choices[i]);
    return s;
  }
  std::string s = std::string(kind == Kind::integer ? "an integer" : "a number") + " in [" + format_number(lo) + ", " +
                  format_number(hi) + "]";
  return s;
}

std::string ParamInfo::check(double v) const {
  if (allows(v)) return {};
  std::string shown = kind == Kind::choice ? std::string("index ") + format_number(v) : format_number(v);
  return std::string(name) + " = " + shown + " is out of range: must be " + range_text();
}

std::optional<double> ParamInfo::choice_index(std::string_view value) const {
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (choices[i] == value) return double(i);
  return std::nullopt;
}

const std::vector<ParamInfo>& param_table() {
  static const std::vector<ParamInfo> table = make_table();
  return table;
}

const ParamInfo* find_param(std::string_view name) {
  for (const ParamInfo& p : param_table())
    if (p.name == name) return &p;
  return nullptr;
}

std::string check_ranges(const RunParams& p) {
  for (const ParamInfo& info : param_table())
    if (const double v = info.get(p); !info.allows(v)) return info.check(v);
  return {};
}

std::string variant_name(const RunParams& p) {
  if (p.planner != Planner::arnold) return to_string(p.planner);  // only the Arnold family has techniques
  std::string s;
  auto add = [&](const char* part) {
    if (!s.empty()) s += '+';
    s += part;
  };
  // Another flow in place of the Arnold flow leads the name (its runs never
  // group with Arnold's): "lorenz", "lorenz+scaling", ...
  if (p.system != arnold_system) add(std::string(system_name(p.system)).c_str());
  if (p.index_switching) add("index_switching");
  if (p.map_zoning) add("map_zoning");
  if (p.f != 1.0) add("scaling");
  return s.empty() ? "original" : s;
}

const char* to_string(Planner v) {
  switch (v) {
    case Planner::arnold:
      return "arnold";
    case Planner::logistic:
      return "logistic";
    case Planner::chebyshev:
      return "chebyshev";
    case Planner::contraction:
      return "contraction";
    case Planner::bouncing:
      return "bouncing";
    case Planner::random_walk:
      return "random_walk";
    case Planner::random_bounce:
      return "random_bounce";
    case Planner::lawnmower:
      return "lawnmower";
  }
  return "?";
}
const char* to_string(ContractionMode v) {
  switch (v) {
    case ContractionMode::map:
      return "map";
    case ContractionMode::loop:
      return "loop";
    case ContractionMode::mirror:
      return "mirror";
  }
  return "?";
}
const char* to_string(ChebTransform v) {
  switch (v) {
    case ChebTransform::none:
      return "none";
    case ChebTransform::arcsine:
      return "arcsine";
    case ChebTransform::arccosine:
      return "arccosine";
  }
  return "?";
}
const char* to_string(Boundary v) { return v == Boundary::mirror ? "mirror" : "fold"; }
const char* to_string(Integrator v) { return v == Integrator::rk4 ? "rk4" : "rk4-doubling"; }
const char* to_string(Sampling v) { return v == Sampling::segments ? "segments" : "points"; }
const char* to_string(SegmentKind v) {
  switch (v) {
    case SegmentKind::start:
      return "start";
    case SegmentKind::arnold:
      return "arnold";
    case SegmentKind::transit:
      return "transit";
    case SegmentKind::logistic:
      return "logistic";
    case SegmentKind::chebyshev:
      return "chebyshev";
    case SegmentKind::subgoal:
      return "subgoal";
    case SegmentKind::move:
      return "move";
  }
  return "?";
}

const char* to_string(Status v) {
  switch (v) {
    case Status::ok:
      return "ok";
    case Status::timeout:
      return "timeout";
    case Status::diverged:
      return "diverged";
    case Status::stuck:
      return "stuck";
    case Status::invalid:
      return "invalid";
    case Status::error:
      return "error";
  }
  return "?";
}

}  // namespace chaosweep
