#pragma once
// Seed 002's analysis (Algorithms 2-3) on our reconstruction of its map:
// each bouncing policy's limiting distribution over position cells, the
// mixture alpha closest to uniform coverage, and the navigation plans by the
// number of bouncing angles they use. Computed, not read from result files.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "analysis/text_table.hpp"
#include "kernels/planners/bouncing/bouncing_cells.hpp"

namespace chaosweep {

struct BouncingPaperOptions {
  std::string env = "seed002_map";                // environment name or file
  int bins = 360;                                 // orientation bins (the paper: 1 degree)
  std::vector<double> angles{30.0, 75.0, 315.0};  // policies, degrees
  double eps = 5.0, r = 0.8;
  // Eq. 5's fit: over the N configuration cells ("b is the n-vector where
  // n = N", as written), or over the free position cells (the marginals).
  enum class Fit { configurations, positions } fit = Fit::configurations;
  int plan_sources = 64;  // sources of Algorithm 2, spread over the configurations
  double w2 = 2.0;        // roadmap weight of a policy change (w1 = 1)
};

// One fit of Eq. 5: the mixture on the simplex closest to uniform b.
struct BouncingPaperFit {
  Eigen::VectorXd alpha;
  double residual = 0;                  // ||Pi alpha - b||
  std::vector<double> single_residual;  // ||Pi e_i - b|| per policy
};

struct BouncingPaperAnalysis {
  bouncing_paper::CellGrid grid;
  Eigen::MatrixXd Pi;     // column i: policy i's limiting distribution over free position cells
  Eigen::VectorXd alpha;  // the best mixture of the chosen fit (opt.fit)
  double residual = 0;    // its ||Pi alpha - b|| in that fit's space
  BouncingPaperFit by_configuration, by_position;  // both fits
  std::vector<int> persistent_groups;
};

BouncingPaperAnalysis analyse_seed002(const BouncingPaperOptions& opt);

// Rows: alpha per policy of both fits (ours, the paper's), residuals,
// persistent groups, and plans by the number of distinct angles they use,
// with opt's angles, bins and w2 and with the paper's navigation setting
// (Figs. 7-8: {45, 90, 135} degrees, 8 orientations, w2 = 100).
TextTable seed002_table(const BouncingPaperOptions& opt);

}  // namespace chaosweep
