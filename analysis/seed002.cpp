#include "seed002.hpp"

#include <set>
#include <sstream>

#include "all_pairs_plans.hpp"
#include "environment_loader.hpp"
#include "markov_chain.hpp"
#include "param_table.hpp"
#include "policy_mixture.hpp"
#include "result_set.hpp"
#include "roadmap.hpp"

namespace chaosweep {

namespace {

// The paper's mixture for {30, 75, 315} degrees, eps 5, r 0.8 (docs/spec.md §5).
constexpr double paper_alpha[3] = {0.221, 0.280, 0.499};

bool paper_setting(const Seed002Options& o) {
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

Seed002Analysis analyse_seed002(const Seed002Options& opt) {
  if (opt.bins < 4 || opt.bins > 3600) throw AnalysisError("--bins must be in [4, 3600]");
  Environment env;
  try {
    env = load_environment(opt.env, 15, 15);
  } catch (const std::exception& e) {
    throw AnalysisError(e.what());
  }
  Seed002Analysis a;
  a.grid = seed002::make_grid(env, 1.0, opt.bins);
  const int n = a.grid.num_free(), k = int(opt.angles.size());
  a.Pi.resize(n, k);
  for (int i = 0; i < k; ++i) {
    const seed002::Limit lim =
        seed002::limiting_distribution(seed002::transition_matrix(seed002::build_cell_map(a.grid, opt.angles[std::size_t(i)], opt.eps, opt.r)));
    a.Pi.col(i) = seed002::position_marginal(a.grid, lim.pi);
    a.persistent_groups.push_back(lim.groups);
  }
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(n, 1.0 / n);
  const seed002::Mixture m = seed002::best_mixture(a.Pi, b);
  a.alpha = m.alpha;
  a.residual = m.residual;
  for (int i = 0; i < k; ++i) a.single_residual.push_back(seed002::mixture_residual(a.Pi, b, Eigen::VectorXd::Unit(k, i)));
  return a;
}

TextTable seed002_table(const Seed002Options& opt) {
  const Seed002Analysis a = analyse_seed002(opt);
  const bool paper = paper_setting(opt);
  TextTable t;
  t.title = "Seed 002: bouncing policies on " + opt.env + " (" + std::to_string(a.grid.num_free()) +
            " free cells x " + std::to_string(opt.bins) + " bins), eps " + format_number(opt.eps) + ", r " +
            format_number(opt.r);
  t.header = {"quantity", "policy", "ours", "paper"};
  for (std::size_t i = 0; i < opt.angles.size(); ++i) {
    const std::string pol = format_number(opt.angles[i]) + " deg";
    t.add_row({"mixture weight alpha", pol, fixed_cell(a.alpha(Eigen::Index(i)), 3), paper && i < 3 ? fixed_cell(paper_alpha[i], 3) : "-"});
  }
  for (std::size_t i = 0; i < opt.angles.size(); ++i)
    t.add_row({"||Pi e_i - b|| (the policy alone)", format_number(opt.angles[i]) + " deg", sig_cell(a.single_residual[i], 4), "-"});
  t.add_row({"||Pi alpha - b|| (the mixture)", "all", sig_cell(a.residual, 4), "-"});
  for (std::size_t i = 0; i < opt.angles.size(); ++i)
    t.add_row({"persistent groups", format_number(opt.angles[i]) + " deg", std::to_string(a.persistent_groups[i]), "-"});
  // Algorithm 2 from sources spread over the configurations (exact bumps:
  // plans are for the nominal policies, eps = 0).
  const seed002::Roadmap rm = seed002::build_roadmap(a.grid, opt.angles, 1.0, 2.0);
  std::vector<int> sources;
  const int step = std::max(1, a.grid.num_configs() / std::max(1, opt.plan_sources));
  for (int c = 0; c < a.grid.num_configs() && int(sources.size()) < opt.plan_sources; c += step) sources.push_back(c);
  std::vector<long> by_count(opt.angles.size() + 1, 0);
  long unreachable = 0, total = 0;
  for (const seed002::PlanRow& row : all_pairs_plans(rm, sources)) {
    for (std::size_t g = 0; g < row.plans.size(); ++g) {
      ++total;
      if (row.weights[g] < 0) {
        ++unreachable;
        continue;
      }
      ++by_count[std::size_t(angles_used(row.plans[g]))];
    }
  }
  for (std::size_t c = 0; c < by_count.size(); ++c)
    t.add_row({"plans using " + std::to_string(c) + " bouncing angle" + (c == 1 ? "" : "s") + " (%)",
               std::to_string(sources.size()) + " sources", fixed_cell(100.0 * double(by_count[c]) / double(total), 2), "-"});
  t.add_row({"unreachable goals (%)", std::to_string(sources.size()) + " sources",
             fixed_cell(100.0 * double(unreachable) / double(total), 2), "-"});
  t.notes.push_back("alpha >= 0, sum 1, minimises ||Pi alpha - b|| with b uniform over free cells (exact over all "
                    "support sets). Plans: Dijkstra on the roadmap (w1 = 1 same policy, w2 = 2 policy change); the "
                    "map is our reconstruction (docs/seed002.md), so alpha differs from the paper's.");
  return t;
}

}  // namespace chaosweep
