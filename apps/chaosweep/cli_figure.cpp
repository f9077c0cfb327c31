// `chaosweep figure NAME RESULTS.h5... -o FILE.png`
#include <iostream>
#include <memory>

#include "analysis/figures.hpp"
#include "analysis/grouping.hpp"
#include "apps/chaosweep/cli_common.hpp"
#include "apps/chaosweep/cli_subcommands.hpp"

namespace chaosweep {

void add_figure_command(CLI::App& app, std::function<int()>& action) {
  auto* cmd =
      app.add_subcommand("figure", "Draw a figure from result files (PNG, SVG, PDF or EPS) and its data as CSV");
  cmd->footer(
      "Figures (each also writes its data as CSV beside the image, FILE.csv):\n"
      "  fig6a       minimum CT over B as a colour map over (A, C); --mark A,B,C (default the\n"
      "              paper's 0.5,0.25,0.25)\n"
      "  fig6b       share of (A, B, C) tuples reaching the target within each time bound up to\n"
      "              --bound (default: the runs' max_time); prints the marked tuple's percentile\n"
      "  heatmap     --stat (min, q1, median, mean, q3, max, ok_rate, runs) over --x and --y\n"
      "  line        --stat (default median) of column --y over column --x, a line per --by value\n"
      "  trajectory  one run (--run ID) replayed over its map: path, transits, obstacles, zone\n"
      "              midpoints, covered cells\n"
      "  coverage    coverage vs time of several runs (--run ID, repeatable) or of the median\n"
      "              run of each value of --by COLUMN\n"
      "  ct_distribution  per file (A.h5 B.h5 ...) and group of --by COL1,COL2: the coverage-time\n"
      "              distribution (ECDF), each curve topping out at its share of ok runs; at most 12\n"
      "              curves\n"
      "  leaderboard the leaderboard's planners (--by, as `table leaderboard`) in its order: the share\n"
      "              of each one's runs over every map within a PR (log axis)\n"
      "  cheb_histogram, cheb_lyapunov  seed 001's Chebyshev map: orbit histogram raw and\n"
      "              transformed; Lyapunov exponent over k (computed, no result file)\n"
      "  seed002_limit  seed 002: the best bouncing-policy mixture's limiting distribution\n"
      "              over the map (computed; --bins)\n"
      "Example: chaosweep figure fig6a out/fig6/results.h5 -o out/fig6/fig6a.png");
  struct Opts {
    std::string name, out, mark, mark_label = "automatic", size = "800x600";
    std::vector<std::string> where;
    std::vector<std::string> files;
    FigureOptions fig;
    bool force = false;
  };
  auto o = std::make_shared<Opts>();
  add_name_and_results(*cmd, o->name, o->files, figure_names(), figure_needs_results);
  cmd->add_option("-o,--output", o->out, "image file: .png, .svg, .pdf or .eps")->required();
  add_force_flag(*cmd, o->force);
  cmd->add_option("--x", o->fig.x, "heatmap: column on the x axis");
  cmd->add_option("--y", o->fig.y, "heatmap: column on the y axis");
  auto* stat = cmd->add_option("--stat", o->fig.stat, "heatmap, line: statistic, " + names_or(statistic_names()))
                   ->capture_default_str();
  cmd->add_option("--mark", o->mark, "fig6a/fig6b: the tuple to mark, A,B,C");
  cmd->add_option("--mark-label", o->mark_label,
                  "fig6a/fig6b: where the mark's label goes: automatic (inside the frame, off the curve), right, "
                  "left, above, below, above_right, below_right, above_left, below_left")
      ->capture_default_str();
  cmd->add_option("--bound", o->fig.bound, "fig6b: time bound, s")->check(CLI::Range(0.0, 1e12));
  cmd->add_option("--run", o->fig.runs, "trajectory/coverage: run_id (repeatable)");
  cmd->add_option("--by", o->fig.by,
                  "coverage: one run per value of this column; line: one line per value; ct_distribution: a curve "
                  "per file and value of these columns (comma-separated); leaderboard: the planner columns");
  cmd->add_option("--where", o->where, "keep rows with COLUMN=VALUE (repeatable; all must hold)");
  cmd->add_option("--bins", o->fig.bins, "seed002_limit: orientation bins")->check(CLI::Range(4, 3600));
  cmd->add_option("--policy", o->fig.policy, "seed002_limit: 0 the best mixture (default), i the i-th policy alone");
  cmd->add_option("--size", o->size, "image size in pixels, WIDTHxHEIGHT")->capture_default_str();
  cmd->callback([o, stat, &action] {
    o->fig.stat_default = stat->count() == 0;
    action = [o]() -> int {
      return run_reporting<AnalysisError>("figure", [&]() -> int {
        o->fig.size = parse_image_size(o->size);
        o->fig.mark_label = parse_label_side(o->mark_label);
        check_output_free(o->out, o->force);
        check_output_free(csv_beside(o->out), o->force, "-o (the CSV beside the image)");
        for (const std::string& v : split_list(o->mark)) {
          try {
            o->fig.mark.push_back(std::stod(v));
          } catch (const std::exception&) {
            throw AnalysisError("--mark: '" + v + "' is not a number");
          }
        }
        const bool needs = figure_needs_results(o->name);
        if (needs && o->files.empty()) throw AnalysisError("give one or more result files (.h5)");
        const FigureOutput out =
            figure_per_file(o->name)
                ? make_per_file_figure(o->name, o->files, o->where, o->fig, o->out)
                : make_figure(o->name, needs ? ResultSet::load(o->files).where(o->where) : ResultSet{}, o->fig, o->out);
        for (const std::string& line : out.lines) std::cout << line << "\n";
        std::cout << "wrote " << out.image << " and " << out.csv << "\n";
        return exit_ok;
      });
    };
  });
}

}  // namespace chaosweep
