#include "analysis/papers/bouncing_paper.hpp"

#include <set>
#include <sstream>

#include "analysis/result_set.hpp"
#include "engine/run/all_pairs_plans.hpp"
#include "engine/spec/environment_loader.hpp"
#include "kernels/core/param_table.hpp"
#include "kernels/planners/bouncing/markov_chain.hpp"
#include "kernels/planners/bouncing/policy_mixture.hpp"
#include "kernels/planners/bouncing/roadmap.hpp"

namespace chaosweep {

namespace {

// The paper's mixture for {30, 75, 315} degrees, eps 5, r 0.8 (docs/spec.md §5).
constexpr double paper_alpha[3] = {0.221, 0.280, 0.499};

bool paper_setting(const BouncingPaperOptions& o) {
  return o.angles == std::vector<double>{30.0, 75.0, 315.0} && o.eps == 5.0 && o.r == 0.8;
}

// Distinct bouncing angles in an observation string ("0" per forward step,
// "<angle>°" per bump).
int angles_used(const std::string& plan) {
  std::set<std::string> seen;
  std::string token;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (plan.compare(i, 2, "\u00b0") == 0) {
      seen.insert(token);
      token.clear();
      ++i;
      continue;
    }
    if (plan[i] == '0' && token.empty()) continue;  // a forward step
    token += plan[i];
  }
  return int(seen.size());
}

}  // namespace

namespace {

BouncingPaperFit fit_mixture(const Eigen::MatrixXd& Pi) {
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(Pi.rows(), 1.0 / double(Pi.rows()));
  const bouncing_paper::Mixture m = bouncing_paper::best_mixture(Pi, b);
  BouncingPaperFit f{m.alpha, m.residual, {}};
  for (Eigen::Index i = 0; i < Pi.cols(); ++i)
    f.single_residual.push_back(bouncing_paper::mixture_residual(Pi, b, Eigen::VectorXd::Unit(Pi.cols(), i)));
  return f;
}

// Algorithm 2 from sources spread over the configurations (exact bumps:
// plans are for the nominal policies, eps = 0): the share of plans using
// 0..k distinct angles, then the share of unreachable goals (percent).
std::vector<double> plans_by_angles(const Environment& env, int bins, const std::vector<double>& angles, double w2,
                                    int max_sources, int& sources_used) {
  const bouncing_paper::CellGrid grid = bouncing_paper::make_grid(env, 1.0, bins);
  const bouncing_paper::Roadmap rm = bouncing_paper::build_roadmap(grid, angles, 1.0, w2);
  std::vector<int> sources;
  const int step = std::max(1, grid.num_configs() / std::max(1, max_sources));
  for (int c = 0; c < grid.num_configs() && int(sources.size()) < max_sources; c += step) sources.push_back(c);
  sources_used = int(sources.size());
  std::vector<double> share(angles.size() + 2, 0.0);
  long total = 0;
  for (const bouncing_paper::PlanRow& row : all_pairs_plans(rm, sources))
    for (std::size_t g = 0; g < row.plans.size(); ++g) {
      ++total;
      share[row.weights[g] < 0 ? angles.size() + 1 : std::size_t(angles_used(row.plans[g]))] += 1.0;
    }
  for (double& v : share) v *= 100.0 / double(total);
  return share;
}

}  // namespace

BouncingPaperAnalysis analyse_seed002(const BouncingPaperOptions& opt) {
  if (opt.bins < 4 || opt.bins > 3600) throw AnalysisError("--bins must be in [4, 3600]");
  Environment env;
  try {
    env = load_environment(opt.env, 15, 15);
  } catch (const std::exception& e) {
    throw AnalysisError(e.what());
  }
  BouncingPaperAnalysis a;
  a.grid = bouncing_paper::make_grid(env, 1.0, opt.bins);
  const int n = a.grid.num_free(), k = int(opt.angles.size());
  a.Pi.resize(n, k);
  Eigen::MatrixXd Pi_config(a.grid.num_configs(), k);
  for (int i = 0; i < k; ++i) {
    const bouncing_paper::Limit lim = bouncing_paper::limiting_distribution(bouncing_paper::transition_matrix(
        bouncing_paper::build_cell_map(a.grid, opt.angles[std::size_t(i)], opt.eps, opt.r)));
    Pi_config.col(i) = lim.pi;
    a.Pi.col(i) = bouncing_paper::position_marginal(a.grid, lim.pi);
    a.persistent_groups.push_back(lim.groups);
  }
  a.by_configuration = fit_mixture(Pi_config);
  a.by_position = fit_mixture(a.Pi);
  const BouncingPaperFit& chosen =
      opt.fit == BouncingPaperOptions::Fit::configurations ? a.by_configuration : a.by_position;
  a.alpha = chosen.alpha;
  a.residual = chosen.residual;
  return a;
}

TextTable seed002_table(const BouncingPaperOptions& opt) {
  const BouncingPaperAnalysis a = analyse_seed002(opt);
  const bool paper = paper_setting(opt);
  TextTable t;
  t.title = "Seed 002: bouncing policies on " + opt.env + " (" + std::to_string(a.grid.num_free()) + " free cells x " +
            std::to_string(opt.bins) + " bins = " + std::to_string(a.grid.num_configs()) + " configurations), eps " +
            format_number(opt.eps) + ", r " + format_number(opt.r);
  t.header = {"quantity", "policy", "ours", "paper"};
  const std::pair<const char*, const BouncingPaperFit*> fits[] = {
      {"configurations (Eq. 5 as written: n = N)", &a.by_configuration}, {"position cells", &a.by_position}};
  for (const auto& [space, fit] : fits) {
    for (std::size_t i = 0; i < opt.angles.size(); ++i) {
      const std::string pol = format_number(opt.angles[i]) + " deg";
      t.add_row({std::string("mixture weight alpha fitted on ") + space, pol,
                 fixed_cell(fit->alpha(Eigen::Index(i)), 3), paper && i < 3 ? fixed_cell(paper_alpha[i], 3) : "-"});
    }
    for (std::size_t i = 0; i < opt.angles.size(); ++i)
      t.add_row({std::string("||Pi e_i - b|| (the policy alone) on ") + space, format_number(opt.angles[i]) + " deg",
                 sig_cell(fit->single_residual[i], 4), "-"});
    t.add_row({std::string("||Pi alpha - b|| (the mixture) on ") + space, "all", sig_cell(fit->residual, 4), "-"});
  }
  for (std::size_t i = 0; i < opt.angles.size(); ++i)
    t.add_row(
        {"persistent groups", format_number(opt.angles[i]) + " deg", std::to_string(a.persistent_groups[i]), "-"});
  // Plans: ours (opt's angles, bins, w2) and the paper's navigation setting
  // (Figs. 7-8 on its maps of Figs. 1-2: {45, 90, 135} deg, 8 orientations,
  // w2 = 100), on this map; the 8-orientation roadmap is small enough for
  // every source.
  Environment env = load_environment(opt.env, 15, 15);
  struct Setting {
    std::vector<double> angles;
    int bins;
    double w2;
    int sources;
  };
  // With w2 = w1 the roadmap is the paper's union of per-policy graphs, in
  // which every rotation costs w1 (its w2 never applies, docs/seed002.md).
  for (const Setting& s : {Setting{opt.angles, opt.bins, opt.w2, opt.plan_sources},
                           Setting{{45.0, 90.0, 135.0}, 8, 100.0, a.grid.num_free() * 8},
                           Setting{{45.0, 90.0, 135.0}, 8, 1.0, a.grid.num_free() * 8}}) {
    std::string name;
    for (double phi : s.angles) name += (name.empty() ? "{" : ", ") + format_number(phi);
    int used = 0;
    const auto share = plans_by_angles(env, s.bins, s.angles, s.w2, s.sources, used);
    name += "} deg, " + std::to_string(s.bins) + " bins, w2 " + format_number(s.w2) + ", " + std::to_string(used) +
            " sources";
    for (std::size_t c = 0; c + 1 < share.size(); ++c)
      t.add_row({"plans using " + std::to_string(c) + " bouncing angle" + (c == 1 ? "" : "s") + " (%)", name,
                 fixed_cell(share[c], 2), "-"});
    t.add_row({"unreachable goals (%)", name, fixed_cell(share.back(), 2), "-"});
  }
  t.notes.push_back(
      "alpha >= 0, sum 1, minimises ||Pi alpha - b|| with b uniform (exact over all support sets): "
      "over the configurations as Eq. 5 is written (n = N), and over the free position cells (the "
      "policies' marginals). Plans: Dijkstra on the roadmap (w1 = 1 same policy, w2 a policy change), "
      "exact turns; the map is our reconstruction (docs/seed002.md), so alpha differs from the paper's, "
      "and the paper's plan shares (Figs. 7-8) are for its other maps (Figs. 1-2).");
  return t;
}

}  // namespace chaosweep
