// `chaosweep table NAME RESULTS.h5...`
#include <iostream>
#include <memory>

#include "analysis/grouping.hpp"
#include "analysis/tables.hpp"
#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"

namespace chaosweep {

void add_table_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd = app.add_subcommand("table", "Print a table from result files (Markdown, CSV or LaTeX)");
  cmd->footer(
      "Tables:\n"
      "  table1   seed 000's Table 1: per case (the runs' label, else size/SR/env/variant) the\n"
      "           best (c, DSindex, f) by median CT, its CT, improvement over the same map's\n"
      "           original Arnold, PR; --paper CSV adds the paper's CT (experiments/table1_paper.csv)\n"
      "  best     the --top K parameter tuples per --by group, by median CT (timeouts count as\n"
      "           infinite); parameters: --params, else those that vary\n"
      "  summary  per --by group (default: variant): runs, ok rate, CT quantiles, median PR\n"
      "  leaderboard  per map (env, size, SR) the planners (--by, default: label, else variant)\n"
      "           ranked by median CT, with ok rate, PR, coverage, visit evenness, turn entropy;\n"
      "           and each planner's mean rank over the maps\n"
      "  seed001  seed 001's Chebyshev-map numbers (Lyapunov exponents, v(xy)) beside ours;\n"
      "           computed, no result file\n"
      "  seed002  seed 002's policy mixture alpha for {30, 75, 315} deg beside the paper's (Eq. 5\n"
      "           fitted on the configurations and on the position cells), and plans by bouncing\n"
      "           angles used (ours and the paper's {45, 90, 135} deg, 8 bins, w2 100), on\n"
      "           experiments/envs/seed002_map (computed)\n"
      "  seed003  seed 003's Tables 1-3, loop and mirror mapping beside ours, from the results\n"
      "           of experiments/seed003.toml\n"
      "  readings Table 1 rows under readings of the paper (experiments/table1_readings.toml):\n"
      "           per reading (--by, else the reading parameters that vary) and row, CT beside\n"
      "           --paper's, and each obstacle row's ratio to its open-map row beside the paper's\n"
      "  tune     a file of chaosweep tune: per case the configuration chosen, its median CT\n"
      "           on the validation seeds with a bootstrap interval, the race runs spent; the\n"
      "           grid's validated best beside it (tune --grid); --grid GRID.h5 adds the grid's\n"
      "           best on its own seeds and its runs\n"
      "Example: chaosweep table best out/fig6/results.h5 --top 10");
  struct Opts {
    std::string name, format = "md", out, by, params;
    std::vector<std::string> where;
    std::vector<std::string> files;
    TableOptions table;
    bool force = false;
  };
  auto o = std::make_shared<Opts>();
  add_name_and_results(*cmd, o->name, o->files, table_names(), table_needs_results);
  cmd->add_option("--format", o->format, "md, csv or tex")->capture_default_str();
  cmd->add_option("-o,--output", o->out, "write to this file instead of standard output");
  add_force_flag(*cmd, o->force);
  cmd->add_option("--by", o->by, "group columns, comma-separated (best, summary, readings; leaderboard: the planner)");
  cmd->add_option("--params", o->params, "parameter columns, comma-separated (best, tune)");
  cmd->add_option("--where", o->where, "keep rows with COLUMN=VALUE (repeatable; all must hold)");
  cmd->add_option("--bins", o->table.bins, "seed002: orientation bins (360: the paper's 1 degree; about a minute)")
      ->check(CLI::Range(4, 3600));
  cmd->add_option("--top", o->table.top, "tuples per group (best)")->check(CLI::Range(1, 1000000));
  cmd->add_option("--paper", o->table.paper, "table1, readings: CSV with row,paper_ct,paper_pr")
      ->check(CLI::ExistingFile);
  cmd->add_option("--grid", o->table.grid, "tune: a grid search's results (.h5), its best per case beside")
      ->check(CLI::ExistingFile);
  cmd->callback([o, &action] {
    action = [o]() -> int {
      return run_reporting<AnalysisError>("table", [&]() -> int {
        const TableFormat f = parse_table_format(o->format);
        check_output_free(o->out, o->force);
        o->table.by = split_list(o->by);
        o->table.params = split_list(o->params);
        const bool needs = table_needs_results(o->name);
        if (needs && o->files.empty()) throw AnalysisError("give one or more result files (.h5)");
        ResultSet rs;
        if (needs) {
          // Only the columns the table reads, and those --where tests.
          TableColumns cols = table_columns(o->name, o->table);
          for (const std::string& w : o->where) cols.columns.push_back(w.substr(0, w.find('=')));
          rs = cols.all ? ResultSet::load(o->files) : ResultSet::load(o->files, cols.columns, cols.if_varying);
          if (!o->where.empty()) rs = rs.where(o->where);  // (a copy of the rows kept)
        }
        const TextTable t = make_table(o->name, rs, o->table);
        if (o->out.empty()) {
          t.write(std::cout, f);
          return exit_ok;
        }
        t.write_file(o->out, f);
        return exit_ok;
      });
    };
  });
}

}  // namespace chaosweep
