#pragma once
// Seed 002's analysis (Algorithms 2-3) on our reconstruction of its map:
// each bouncing policy's limiting distribution over position cells, the
// mixture alpha closest to uniform coverage, and the navigation plans by the
// number of bouncing angles they use. Computed, not read from result files.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "bouncing_cells.hpp"
#include "text_table.hpp"

namespace chaosweep {

struct Seed002Options {
  std::string env = "seed002_map";                 // environment name or file
  int bins = 360;                                  // orientation bins (the paper: 1 degree)
  std::vector<double> angles{30.0, 75.0, 315.0};  // policies, degrees
  double eps = 5.0, r = 0.8;
  int plan_sources = 64;  // sources of Algorithm 2, spread over the configurations
};

struct Seed002Analysis {
  seed002::CellGrid grid;
  Eigen::MatrixXd Pi;     // column i: policy i's limiting distribution over free position cells
  Eigen::VectorXd alpha;  // the best mixture
  double residual = 0;    // ||Pi alpha - b||
  std::vector<double> single_residual;
  std::vector<int> persistent_groups;
};

Seed002Analysis analyse_seed002(const Seed002Options& opt);

// Rows: alpha per policy (ours, the paper's), residuals, persistent groups,
// and plans by the number of distinct angles they use.
TextTable seed002_table(const Seed002Options& opt);

}  // namespace chaosweep
