#pragma once
// Seed 002 (docs/spec.md §5): the bouncing robot's cell configuration space and its
// generalized cell-to-cell mapping (GCM), one policy (bouncing angle) at a time.
//
// Model (paper Eq. 3, reconstructed): one GCM step moves the robot forward by
// `step` metres along its heading. If the end point is free the heading is
// kept (observation '0'); otherwise the robot bumps, stays in its position
// cell and rotates counter-clockwise by phi (+- eps). A heading that still
// points into the wall bumps again on the next step (the paper's plans show
// consecutive bumps, "135 135").
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep::bouncing_paper {

// Position cells (square grid of side `cell` over [0,lx] x [0,ly]) x
// orientation bins (bin k is centred on k * 360/bins degrees). Only free
// position cells (centre outside every obstacle) get configuration indices:
// config = free_index * bins + bin.
struct CellGrid {
  Environment env;
  double cell = 1.0;
  int nx = 0, ny = 0, bins = 0;
  std::vector<int> free_index;  // position cell (ix + nx*iy) -> free index or -1
  std::vector<int> free_cells;  // free index -> position cell

  int num_free() const { return static_cast<int>(free_cells.size()); }
  int num_configs() const { return num_free() * bins; }
  int config(int free, int bin) const { return free * bins + bin; }
  int free_of(int config) const { return config / bins; }
  int bin_of(int config) const { return config % bins; }
  double bin_width_deg() const { return 360.0 / bins; }
  // Free index of the position cell holding (x, y), or -1 (outside / not free).
  int free_at(double x, double y) const;
  std::pair<double, double> centre(int free) const;
};

CellGrid make_grid(const Environment& env, double cell, int bins);

// Where a robot driving straight from (x, y) at heading_deg first touches a
// wall or obstacle: the contact point, the free cell it is in (-1 if none)
// and the outward normal of the surface it hit (pointing back into free space).
struct Contact {
  double x, y, distance;
  int free;
  double normal_x, normal_y;
};
std::optional<Contact> drive_to_contact(const CellGrid& grid, double x, double y, double heading_deg);

// Rotation by phi +- eps as bin offsets from the current bin (the current
// heading is taken at its bin centre): with probability r exactly phi (the bin
// holding heading+phi), with probability 1-r uniform on [phi-eps, phi+eps],
// split over bins by overlap length. Sorted by offset, merged, weights sum 1.
std::vector<std::pair<int, double>> rotation_offsets(int bins, double phi_deg, double eps_deg, double r);

struct GcmOptions {
  double step = 0.0;  // forward step per GCM step, metres; 0 = one cell side
  int samples = 2;    // sample points per axis per position cell (samples^2 in all)
};

// One policy's cell-to-cell map in CSR form: row z lists (to, probability,
// bump?) with targets sorted and merged, probabilities summing to 1.
struct CellMap {
  int n = 0;
  std::vector<int> row_start;  // n + 1
  std::vector<int> to;
  std::vector<double> prob;
  std::vector<std::uint8_t> bump;  // 1: the transition is a bump + rotation
};

CellMap build_cell_map(const CellGrid& grid, double phi_deg, double eps_deg, double r, const GcmOptions& opts = {});

}  // namespace chaosweep::bouncing_paper
