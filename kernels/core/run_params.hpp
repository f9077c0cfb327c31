#pragma once
// What a run is (its parameters) and what it yields (its result). A run is a
// pure function RunParams x Environment -> RunResult (docs/spec.md §6).
#include "kernels/systems/cheb_transform.hpp"
#include "kernels/systems/system_info.hpp"

#include <cstdint>
#include <limits>
#include <string>

namespace chaosweep {

// The last three are the baselines (docs/spec.md §7).
enum class Planner { arnold, logistic, chebyshev, contraction, bouncing, random_walk, random_bounce, lawnmower };
enum class Boundary { mirror, fold };
enum class Integrator { rk4, rk4_doubling };
enum class Sampling { segments, points };
// What the coverage tc counts: visited free cells of the free cells (docs/spec.md §1),
// or visited free cells plus the (known) obstacle cells of all cells.
enum class CoverageCells { free_cells, all_cells };
enum class ZoneGoal { free_cell, midpoint };
// MapZoning's ranking of zones: density first on open maps and distance
// first with obstacles (Section 3.2), or always one way (Section 3.2.1's
// "least coverage to highest", Algorithm 2's lines 5-9).
enum class ZoneOrder { automatic, density, distance };
// Eq. 8's reading at obstacle faces: push the point onto the face (as
// printed), mirror it about the face (Eq. 7's form), or mirror it and reverse
// the robot's motion along that axis from then on (a specular bounce, the
// fold's reading at obstacles).
enum class ObstacleResponse { push, mirror, reflect };
// Robot time a transit point costs: dt_c each (Algorithm 4 as printed), or
// its distance from the previous point at speed v.
enum class TransitTime { points, distance };
// Algorithm 4's re-plan after a transit point met an obstacle: a fresh
// Logistic path from the pushed-out point, or the remaining Logistic points
// mapped anew from it (m <- m - i + 1, as printed).
enum class TransitReplan { fresh, reuse };
// The Logistic state of transits: carried on through the run, or also reset
// to its initial value when a zone is dropped (Algorithm 2, lines 36-37).
enum class LogisticReset { never, drop };
enum class Status { ok, timeout, diverged, stuck, invalid, error };
// Seed 003: one mapped trajectory, the complete-coverage loop of contracted
// sections, or the mirror-mapping baseline.
enum class ContractionMode { map, loop, mirror };

inline constexpr double unset = std::numeric_limits<double>::quiet_NaN();

struct RunParams {
  Planner planner = Planner::arnold;
  // The chaotic system driving the Arnold planner family: 0 the Arnold flow,
  // else a flow of kernels/systems/system_list.hpp (Lorenz, Chen, Chua, ...)
  // with coefficients sys_a..sys_d (unset: the flow's defaults).
  int system = arnold_system;
  double sys_a = unset, sys_b = unset, sys_c = unset, sys_d = unset;
  // Arnold flow coefficients (docs/spec.md §2 defaults), and the initial
  // state of the system: unset, its default (Arnold (0, 1, 0), a flow's
  // SystemDefaults::ic), per coordinate; read it with system_ic.
  double A = 0.5, B = 0.25, C = 0.25;
  double ic_x = unset, ic_y = unset, ic_z = unset;
  int ds_index = 3;                         // heading = x (1), y (2) or z (3)
  double f = 1.0;                           // scaling factor (1 = no scaling)
  double v = 1.0;                           // robot speed, m/s
  double dt = 0.1;                          // initial integration step, s
  double ep = 1e-6;                         // step-doubling tolerance, m
  double dt_min = 1e-9;                     // step doubling below this step ends the run as diverged, s
  double fo = 0.5;                          // boundary/obstacle offset, m
  double size_x = 50.0, size_y = 50.0;      // map sides, m (an environment may fix them)
  double sr = 1.0;                          // sensing range = cell side, m
  double start_x = unset, start_y = unset;  // unset: the environment's start, else (fo, fo)
  Boundary boundary = Boundary::mirror;
  ObstacleResponse obstacle_response = ObstacleResponse::push;
  Integrator integrator = Integrator::rk4;
  Sampling sampling = Sampling::segments;
  CoverageCells coverage_cells = CoverageCells::free_cells;
  double dc = 0.9;          // desired coverage
  double max_time = 0.0;    // robot-time budget, s; 0 = auto (max_pr * T_opt)
  double max_pr = 20.0;     // auto budget in multiples of T_opt
  double stuck_time = 0.0;  // end as stuck after this long without a new cell; 0 = never
  int niter = 1000;         // points per segment (SystemScaler call)

  // Control techniques (seed 000, Algorithm 1); scaling is f != 1.
  int index_switching = 0;  // 1: switch DSindex when a segment adds <= switch_min_new cells
  int switch_min_new = 0;
  int map_zoning = 0;  // 1: MapZoning when Eq. 5 fails
  double c = 0.25;     // Eq. 5 coefficient
  int zones_x = 4, zones_y = 4;
  ZoneGoal zone_goal = ZoneGoal::free_cell;  // where a transit to a zone goes
  ZoneOrder zone_order = ZoneOrder::automatic;
  int th = 0;         // transit attempts per zone; 0 = auto (10 * L / 50)
  int dnh = 5;        // th grows by dnh when every zone failed
  double dt_c = 0.1;  // transit / Logistic step, s
  TransitTime transit_time = TransitTime::points;
  TransitReplan transit_replan = TransitReplan::fresh;
  double logistic_r = 4.0, logistic_x0 = 0.1;
  LogisticReset logistic_reset = LogisticReset::never;

  // Chebyshev planner (seed 001): two maps of order cheb_k from cheb_x0 and
  // cheb_y0 give sub-goals in the free rectangles (Eqs. 9-11); the robot, a
  // disc of `radius`, walks straight to each in steps of `step`.
  int cheb_k = 6;
  double cheb_x0 = 0.1, cheb_y0 = 0.10001;
  ChebTransform cheb_transform = ChebTransform::arcsine;
  double radius = 0.1;
  double step = 0.125;
  int loop_subgoals = 200;        // sub-goals per large loop, split over the rectangles by area
  std::int64_t max_subgoals = 0;  // end the run after this many sub-goals (0: no limit)

  // Contraction planner (seed 003): the Arnold robot (A, B, C, ic, ds_index,
  // v, dt) integrated by RK2 for c3_n steps and Map-compressed onto the
  // workplace (map), chained by the contraction transformation until dc
  // with candidates from an ic grid of step c3_ic_grid (loop), or kept in by
  // mirror mapping at the walls (mirror).
  ContractionMode c3_mode = ContractionMode::map;
  int c3_n = 800;
  double c3_ic_grid = 1.0;

  // Bouncing robot (seed 002): drives straight in steps of `step`; at each
  // bump it picks policy i with probability alpha_i (the mixture) and turns
  // counter-clockwise by phi_i, exactly with probability bounce_r, else
  // uniformly within +-bounce_eps; draws seeded by `seed`.
  double bounce_phi1 = 30, bounce_phi2 = 75, bounce_phi3 = 315;  // degrees
  double bounce_alpha1 = 0.221, bounce_alpha2 = 0.280, bounce_alpha3 = 0.499;
  double bounce_eps = 5, bounce_r = 0.8;
  double bounce_heading = 0;  // initial heading, degrees

  // Chaotic spread (docs/spec.md §1): ic perturbed uniformly in +-ic_jitter per
  // coordinate, and logistic_x0 in +-logistic_jitter, drawn from `seed`.
  double ic_jitter = 0.0;
  double logistic_jitter = 0.0;
  std::int64_t seed = 0;
};

// The run's initial state before any jitter: each ic coordinate as set, an
// unset one the system's default (docs/spec.md §2).
inline double or_default(double v, double dflt) { return v != v ? dflt : v; }  // v != v: unset (NaN)

inline Vec3<double> system_ic(const RunParams& p) {
  const SystemDefaults d = system_defaults(p.system);
  return {or_default(p.ic_x, d.ic[0]), or_default(p.ic_y, d.ic[1]), or_default(p.ic_z, d.ic[2])};
}

// sys_a..sys_d as set (NaN: unset).
inline SystemCoeffs<double> set_system_coeffs(const RunParams& p) { return {p.sys_a, p.sys_b, p.sys_c, p.sys_d}; }

// A system's coefficients: the Arnold flow's are seed 000's A, B, C; any
// other's sys_a..sys_d, each unset one the system's default.
inline SystemCoeffs<double> system_coeffs(const RunParams& p) {
  if (p.system == arnold_system) return {p.A, p.B, p.C, 0.0};
  const SystemCoeffs<double> set = set_system_coeffs(p), d = system_defaults(p.system).coeffs();
  return {or_default(set.a, d.a), or_default(set.b, d.b), or_default(set.c, d.c), or_default(set.d, d.d)};
}

struct RunResult {
  Status status = Status::invalid;
  double coverage_time = unset;  // robot time when coverage first reached dc (ok only)
  double final_coverage = 0.0;   // tc at the end (visited free cells / free cells, see coverage_cells)
  std::int64_t steps = 0;        // accepted integration steps
  double t_end = 0.0;            // robot time at the end of the run
  double t_opt = unset;          // lawnmower reference time
  double pr = unset;             // coverage_time / t_opt
  std::int64_t free_cells = 0;
  std::int64_t visited_cells = 0;
  std::int64_t dt_halvings = 0;  // step-doubling halvings
  double final_x = unset, final_y = unset;
  std::int64_t segments = 0;  // Arnold / Logistic segments run; Chebyshev large loops; lawnmower rectangles
  std::int64_t index_switches = 0;
  std::int64_t zonings = 0;           // MapZoning calls
  std::int64_t transits = 0;          // transits that reached their zone midpoint
  std::int64_t zones_dropped = 0;     // zones given up after th attempts
  std::int64_t transit_points = 0;    // mapped points walked on transits
  std::int64_t transit_attempts = 0;  // transit points pushed out of an obstacle (Eq. 8)
  int final_ds_index = 0;
  std::int64_t subgoals = 0;     // Chebyshev sub-goals reached
  std::int64_t reflections = 0;  // seed 003 mirror mapping; seed 002 and random_bounce bumps; random_walk redraws
  double visit_evenness = 0.0;   // Pielou evenness of cell entries over free cells (visit_evenness)
  double turn_entropy = 0.0;     // bits per turn between cell entries (turn_entropy)
  double coverage_area = unset;  // mean first-visit time of the cells dc needs, over T_opt (coverage_area)
  double wall_time = 0.0;        // seconds of CPU wall clock (not part of the pure result)
  std::string message;           // why a run is invalid / errored
};

// Table 1's technique set of a run: "original", "logistic", or the enabled
// switches joined by '+' ("index_switching+map_zoning+scaling").
std::string variant_name(const RunParams& p);

const char* to_string(Planner);
const char* to_string(Boundary);
const char* to_string(Integrator);
const char* to_string(Sampling);
const char* to_string(ChebTransform);
const char* to_string(ContractionMode);
const char* to_string(Status);

}  // namespace chaosweep
