#pragma once
// The coverage grid of docs/spec.md §1: square cells of side SR, ceil(L/SR) per axis
// (the last row/column clipped to the map), a cell free when its centre is not
// inside an obstacle. Tracks visited free cells incrementally.
#include <cstdint>
#include <memory>
#include <vector>

#include "kernels/core/environment.hpp"

namespace chaosweep {

class CoverageGrid {
 public:
  enum Cell : std::uint8_t { unvisited = 0, visited = 1, blocked = 2 };

  CoverageGrid(const Environment& env, double cell_size);

  int nx() const { return nx_; }
  double cell_size() const { return cell_; }
  double inv_cell_size() const { return inv_cell_; }
  int ny() const { return ny_; }
  int free_cells() const { return free_; }
  int blocked_cells() const { return nx_ * ny_ - free_; }
  int visited_cells() const { return visited_; }
  double coverage() const { return free_ > 0 ? double(visited_) / double(free_) : 0.0; }
  Cell at(int i, int j) const { return Cell(cells_[std::size_t(j) * nx_ + i]); }

  // Cell index of a coordinate, clamped into the grid (a point on the far
  // wall belongs to the last cell).
  int cell_x(double x) const { return clamp_index(x * inv_cell_, nx_); }
  int cell_y(double y) const { return clamp_index(y * inv_cell_, ny_); }

  void mark_cell(int i, int j) {
    const std::size_t k = std::size_t(j) * nx_ + i;
    if (long(k) != current_) enter(long(k), i, j);
    std::uint8_t& c = cells_[k];
    if (!stamp_.empty() && c != blocked && stamp_[k] != window_) {
      stamp_[k] = window_;
      ++window_distinct_;
    }
    if (c == unvisited && region_) ++region_visited_[std::size_t((*region_)[k])];
    visited_ += (c == unvisited);
    c = c == unvisited ? std::uint8_t(visited) : c;
  }

  // Whether mark_cell(i, j) would change nothing: the cell marked last,
  // visited (or blocked), and touched in this window already (a transit's
  // points stay about ten to a cell).
  bool marks_nothing(int i, int j) const {
    const long k = long(j) * nx_ + i;
    if (k != current_) return false;
    const std::uint8_t c = cells_[std::size_t(k)];
    return c != unvisited && (stamp_.empty() || c == blocked || stamp_[std::size_t(k)] == window_);
  }

  // Visited cells per region, kept up to date as cells are marked, so that
  // MapZoning's zone densities cost O(zones) instead of a pass over the grid
  // at every zoning attempt. region_of_cell: the region (0 .. regions - 1) of
  // each cell, row-major; counting starts from the grid as it is now.
  void count_regions(std::shared_ptr<const std::vector<int>> region_of_cell, int regions);
  const std::vector<int>* regions() const { return region_.get(); }
  int region_visited(int k) const { return region_visited_[std::size_t(k)]; }

  // Eq. 5 needs the distinct free cells touched in a window (a segment), new
  // or repeated. Counting starts with the first begin_window().
  void begin_window() {
    if (stamp_.empty()) stamp_.assign(cells_.size(), 0);
    ++window_;
    window_distinct_ = 0;
  }
  int window_distinct() const { return window_distinct_; }
  // For the lane integrators, which mark a windowed run's entered cells
  // themselves (LaneArrays::stamp): the window stamps (nullptr before the
  // first window), the window now and the distinct count taken back.
  std::uint32_t* window_stamps() { return stamp_.empty() ? nullptr : stamp_.data(); }
  std::uint32_t window() const { return window_; }
  void set_window_distinct(int n) { window_distinct_ = n; }
  // And the visited counts by region (count_regions; nullptr without).
  const int* region_of_cell() const { return region_ ? region_->data() : nullptr; }
  int* region_visited_counts() { return region_ ? region_visited_.data() : nullptr; }
  // For the lane integrators, which mark entered cells in place
  // (LaneArrays::cells) and count them: the bytes (row-major, nx per row)
  // and the count taken back.
  std::uint8_t* cell_bytes() { return cells_.data(); }
  void set_visited_cells(int n) { visited_ = n; }
  void mark_point(double x, double y) { mark_cell(cell_x(x), cell_y(y)); }
  // Supercover: every cell the closed segment touches, including both side
  // cells where it passes exactly through a grid corner. Inline for the
  // common cases of a step that stays in its cell or enters a side
  // neighbour (both ends in one row or column: the segment touches only
  // those two cells, as the traversal in mark_crossing finds).
  void mark_segment(double x0, double y0, double x1, double y1) {
    const int i = cell_x(x0), j = cell_y(y0);
    const int i1 = cell_x(x1), j1 = cell_y(y1);
    if (i1 == i && j1 == j) mark_cell(i, j);
    else mark_step(i, j, i1, j1, x0, y0, x1, y1);
  }
  // mark_segment for a caller that knows both ends' cells: (x0, y0) in
  // (i, j), (x1, y1) in another cell (i1, j1). Marking the start cell again
  // changes nothing when it is the cell marked last and no window counts
  // touches (the common case of a walk from cell to cell), so that mark is
  // skipped then.
  void mark_step(int i, int j, int i1, int j1, double x0, double y0, double x1, double y1) {
    if (long(j) * nx_ + i != current_ || !stamp_.empty()) mark_cell(i, j);
    const int di = i1 - i, dj = j1 - j;
    if ((di == 0 && (dj == 1 || dj == -1)) || (dj == 0 && (di == 1 || di == -1))) mark_cell(i1, j1);
    else mark_crossing(x0, y0, x1, y1);
  }

  // The coverage-time area (docs/spec.md §1, "Path metrics"): the robot
  // time at which each of the first `needed` visited free cells was first
  // visited, summed. A planner calls note_time(t) after each move with the
  // move's end time (and note_time(0) after marking the start): the cells
  // marked since the last call count at t. Counting starts with
  // count_cover_times (prepare_run).
  void count_cover_times(long needed) { cover_needed_ = needed; }
  void note_time(double t) {
    const long now = visited_ < cover_needed_ ? visited_ : cover_needed_;
    if (now == cover_noted_) return;
    cover_time_sum_ += double(now - cover_noted_) * t;
    cover_noted_ = now;
  }
  long cover_needed() const { return cover_needed_; }
  long cover_noted() const { return cover_noted_; }
  double cover_time_sum() const { return cover_time_sum_; }
  // For the lane integrators, which add each new cell's time as they mark
  // it (LaneArrays::cover_sum): the sum taken back, every visited cell noted.
  void set_cover_time_sum(double s) {
    cover_time_sum_ = s;
    cover_noted_ = visited_ < cover_needed_ ? visited_ : cover_needed_;
  }

  // Path metrics (docs/spec.md §1, "Path metrics"), counted as cells are
  // marked, so every planner has them: each entry into a cell other than
  // the last one marked is a visit of it, and the direction of the move
  // between them (east, north, west, south: 0-3, the longer axis of a jump)
  // turns against the last one's by (dir - last) mod 4: straight, left,
  // back, right.
  const std::vector<std::uint32_t>& visits() const { return visits_; }
  const std::int64_t* turns() const { return turns_; }
  // For the lane integrators, which count their entries in place
  // (LaneArrays::visits, turns, last_dir) and hand the entry state back.
  std::uint32_t* visit_counts() { return visits_.data(); }
  std::int64_t* turn_counts() { return turns_; }
  int last_direction() const { return last_dir_; }
  void set_entry_state(long cell, int last_direction) {
    current_ = cell;
    ci_ = int(cell % nx_);
    cj_ = int(cell / nx_);
    last_dir_ = last_direction;
  }

 private:
  void enter(long k, int i, int j) {
    ++visits_[std::size_t(k)];
    if (current_ >= 0) {
      const int di = i - ci_, dj = j - cj_;
      const int dir = (di < 0 ? -di : di) >= (dj < 0 ? -dj : dj) ? (di > 0 ? 0 : 2) : (dj > 0 ? 1 : 3);
      if (last_dir_ >= 0) ++turns_[(dir - last_dir_) & 3];
      last_dir_ = dir;
    }
    current_ = k;
    ci_ = i;
    cj_ = j;
  }
  void mark_crossing(double x0, double y0, double x1, double y1);
  static int clamp_index(double g, int n) {
    if (!(g > 0.0)) return 0;  // also maps NaN to 0; callers reject NaN first
    const int i = static_cast<int>(g);
    return i < n ? i : n - 1;
  }

  int nx_, ny_, free_ = 0, visited_ = 0;
  double cell_, inv_cell_;
  std::vector<std::uint8_t> cells_;
  std::vector<std::uint32_t> stamp_;  // window id of each cell's last touch
  std::uint32_t window_ = 0;
  int window_distinct_ = 0;
  std::shared_ptr<const std::vector<int>> region_;  // see count_regions
  std::vector<int> region_visited_;
  std::vector<std::uint32_t> visits_;  // entries per cell (see visits())
  std::int64_t turns_[4] = {0, 0, 0, 0};
  long current_ = -1;                        // the cell marked last (-1: none yet), at (ci_, cj_)
  long cover_needed_ = 0, cover_noted_ = 0;  // see count_cover_times
  double cover_time_sum_ = 0.0;
  int ci_ = 0, cj_ = 0, last_dir_ = -1;
};

// Pielou's evenness of the visits over the free cells: the Shannon entropy
// of their shares (a cell never visited has none) over ln(free cells), in
// [0, 1]; 1 when every free cell was entered equally often. 0 for a grid of
// one free cell.
double visit_evenness(const CoverageGrid& g);
// Shannon entropy (bits, in [0, 2]) of the turns between successive cell
// entries (straight, left, back, right); 0 with no turn counted.
double turn_entropy(const CoverageGrid& g);
// The area between the target and the coverage curve, over dc T_opt: the
// mean first-visit time of the cells the target needs (count_cover_times)
// over t_opt, a cell first visited after the last note_time counting at
// t_end and one never visited at the budget (0.5 for a lawnmower that
// covers at a steady pace in T_opt). 0 when the target needs no cell.
double coverage_area(const CoverageGrid& g, double t_end, double budget, double t_opt);

}  // namespace chaosweep
