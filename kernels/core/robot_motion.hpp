#pragma once
// Applies a displacement to the robot and keeps it in the free workspace:
// boundary (Eq. 7 mirror or fold), then obstacles (Eq. 8, read as
// obstacle_response). Records the visited cells on the coverage grid.
#include <algorithm>

#include "kernels/core/boundary.hpp"
#include "kernels/core/coverage_grid.hpp"
#include "kernels/core/environment.hpp"
#include "kernels/core/run_params.hpp"

namespace chaosweep {

class RobotMotion {
 public:
  RobotMotion(const RunParams& p, const Environment& env, CoverageGrid& grid)
      : env_(env),
        grid_(grid),
        boundary_(p.boundary),
        sampling_(p.sampling),
        mirror_(p.obstacle_response != ObstacleResponse::push),
        reflect_(p.obstacle_response == ObstacleResponse::reflect),
        fo_(p.fo),
        x_(p.start_x),
        y_(p.start_y),
        ux_(p.start_x),
        uy_(p.start_y),
        clear_reach_(obstacle_box_reach_cells * grid.cell_size()) {
    grid_.mark_point(x_, y_);
  }

  double x() const { return x_; }
  double y() const { return y_; }
  double unfolded_x() const { return ux_; }
  double unfolded_y() const { return uy_; }
  // Position after steps the lane fast path applied, with the fold
  // boundary's unfolded position (the mirror boundary does not use it).
  void set_position(double x, double y, double ux, double uy) {
    x_ = x;
    y_ = y;
    ux_ = ux;
    uy_ = uy;
  }

  // Puts the robot at (x, y) (a transit point, already kept clear of walls
  // and obstacles), marking the cells on the way.
  void jump_to(double x, double y) {
    const double px = x_, py = y_;
    x_ = ux_ = x;
    y_ = uy_ = y;
    mark(px, py);
  }

  // jump_to for a point (x, y) in cell (i, j), the robot being in cell
  // (ri, rj), when that marks nothing (the cell marked last, nothing new to
  // count: CoverageGrid::marks_nothing); true when it moved the robot, false
  // (nothing done) otherwise. A transit's points fall about ten to a cell.
  bool jump_within(double x, double y, int i, int j, int ri, int rj) {
    if (sampling_ == Sampling::segments && (ri != i || rj != j)) return false;
    if (!grid_.marks_nothing(i, j)) return false;
    x_ = ux_ = x;
    y_ = uy_ = y;
    return true;
  }

  // Always inlined: it runs once per step of every lane.
  [[gnu::always_inline]] void move(double dx, double dy) {
    const double px = x_, py = y_;
    dx *= sx_;  // +-1: exact, so the other responses move by (dx, dy) bit for bit
    dy *= sy_;
    if (boundary_ == Boundary::mirror) {
      x_ = mirror_eq7(x_ + dx, 0.0, env_.lx, fo_);
      y_ = mirror_eq7(y_ + dy, 0.0, env_.ly, fo_);
    } else {
      ux_ += dx;
      uy_ += dy;
      x_ = triangle_fold(ux_, 0.0, env_.lx);
      y_ = triangle_fold(uy_, 0.0, env_.ly);
    }
    if (!env_.obstacles.empty()) push_out();
    mark(px, py);
  }

 private:
  void mark(double px, double py) {
    if (sampling_ == Sampling::segments) grid_.mark_segment(px, py, x_, y_);
    else grid_.mark_point(x_, y_);
  }

  // A box of the map that meets no obstacle's margin (obstacle_box without a
  // near one): keep_out_of_obstacles leaves a position in it where it is, so
  // a move that ends there skips the pass over the obstacles (a fifth of the
  // Logistic planner's time on five squares). The box stays true wherever
  // the robot goes; it is made anew around the robot, after a move that left
  // it, at most every clear_refresh_moves moves: beside an obstacle the robot
  // leaves each new box at once, and a box costs several passes.
  static constexpr int clear_refresh_moves = 8;

  void push_out() {
    if (clear_.contains_closed(x_, y_)) return;
    const double bx = x_, by = y_;
    const ObstacleHit hit = keep_out_of_obstacles(env_, fo_, mirror_, x_, y_);
    if (++since_clear_ >= clear_refresh_moves) {
      since_clear_ = 0;
      clear_ = obstacle_box(env_, fo_, x_, y_, {0.0, 0.0, env_.lx, env_.ly}, clear_reach_, false).box;
    }
    if (!hit.moved) return;
    if (reflect_) {  // a bounce: the motion along each axis reflected an odd number of times reverses
      if (hit.x_faces % 2) sx_ = -sx_;
      if (hit.y_faces % 2) sy_ = -sy_;
    }
    // A push near a wall must not leave the map.
    x_ = std::clamp(x_, 0.0, env_.lx);
    y_ = std::clamp(y_, 0.0, env_.ly);
    if (boundary_ == Boundary::fold) {
      // Carry the correction to the unfolded plane with the fold's local slope.
      ux_ += fold_slope(ux_, 0.0, env_.lx) * (x_ - bx);
      uy_ += fold_slope(uy_, 0.0, env_.ly) * (y_ - by);
    }
  }

  const Environment& env_;
  CoverageGrid& grid_;
  Boundary boundary_;
  Sampling sampling_;
  bool mirror_, reflect_;  // obstacle_response (see ObstacleResponse)
  double fo_;
  double sx_ = 1.0, sy_ = 1.0;  // reflect: the signs the displacement takes (a bounce reverses one)
  double x_, y_;                // position in the map
  double ux_, uy_;              // unfolded position (fold boundary only)
  double clear_reach_;          // how far a clear box reaches from the robot at most
  Rect clear_ = no_rect;        // see push_out
  int since_clear_ = clear_refresh_moves;
};

}  // namespace chaosweep
