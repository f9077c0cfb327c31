// analysis/: what a figure draws that can be checked without looking: pens,
// heatmap cells, the mark and its label's side, the legend's place, axis
// labels, the order of groups, and figure ct_distribution's data and errors.
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include "analysis/column_labels.hpp"
#include "analysis/ct_distribution.hpp"
#include "analysis/figures.hpp"
#include "analysis/grouping.hpp"
#include "analysis/plot.hpp"
#include "analysis/plot_style.hpp"
#include "engine/rows/result_columns.hpp"
#include "engine/store/h5_store.hpp"
#include "kernels/core/param_table.hpp"
#include "tests/support/test_util.hpp"

namespace chaosweep {
namespace {

using test::TempDir;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

TEST(PlotStyle, PensAreDistinctForEveryLineUpToTheStyleCount) {
  std::set<std::string> pens;
  for (std::size_t k = 0; k < line_style_count; ++k) pens.insert(series_pen(k));
  EXPECT_EQ(pens.size(), line_style_count);
  EXPECT_GE(line_style_count, 47u);  // the 47 lines of a `line --by` that used to repeat 8 colours
  EXPECT_EQ(series_pen(0), "b-2");
  EXPECT_EQ(series_pen(8), "b|2");  // the ninth line: the first colour, dashed
  EXPECT_EQ(series_pen(line_style_count), series_pen(0));
  EXPECT_EQ(line_pen(1, 2), "r;2");
}

TEST(PlotStyle, RenderGivesEachLineItsOwnPenAndPutsTheLegendOutside) {
  TempDir dir;
  LinePlot p;
  p.title = "many";
  for (int k = 0; k < 47; ++k) p.series.push_back({"line " + std::to_string(k), {0, 1}, {double(k), double(k) + 1}});
  const RenderReport r = render(p, dir.file("many.png"), {320, 240});
  ASSERT_EQ(r.pens.size(), 47u);
  EXPECT_EQ(std::set<std::string>(r.pens.begin(), r.pens.end()).size(), 47u);
  EXPECT_TRUE(r.legend_outside);
  // One line alone: no legend at all.
  p.series.resize(1);
  EXPECT_FALSE(render(p, dir.file("one.png"), {320, 240}).legend_outside);
  // An explicit colour and dash win over the position.
  p.series[0].colour = 2, p.series[0].dash = 1;
  EXPECT_EQ(render(p, dir.file("one.png"), {320, 240}).pens[0], "g|2");
}

TEST(PlotStyle, LegendLayoutSplitsManyEntriesIntoColumnsAndLeavesThePlotRoom) {
  const LegendLayout few = legend_layout(3, 25);
  EXPECT_EQ(few.columns, 1u);
  EXPECT_EQ(few.rows, 3u);
  const LegendLayout many = legend_layout(47, 8);
  EXPECT_GE(many.columns, 2u);
  EXPECT_GE(many.rows * many.columns, 47u);
  EXPECT_LT(many.rows * (many.columns - 1), 47u);  // no empty column
  EXPECT_LE(many.row * double(many.rows), 1.0);    // the rows fit the axes' height
  for (const LegendLayout& l : {few, many}) {
    EXPECT_GE(l.plot_width, 0.45);
    EXPECT_LE(l.plot_width, 0.9);
  }
  EXPECT_LT(legend_layout(3, 60).plot_width, legend_layout(3, 10).plot_width);  // longer names, more room
}

TEST(PlotStyle, HeatmapCellsAreFlatRectanglesCentredOnTheAxisValues) {
  EXPECT_EQ(cell_edges({0.5, 1.5, 2.5}), (std::vector<double>{0, 1, 2, 3}));
  EXPECT_EQ(cell_edges({1, 2, 4}), (std::vector<double>{0.5, 1.5, 3, 5}));
  EXPECT_EQ(heat_colour(0), "{x000080}");  // the colour bar's ends: dark blue, dark red
  EXPECT_EQ(heat_colour(1), "{x800000}");
  EXPECT_EQ(heat_colour(0.4), "{x00FFFF}");  // cyan, the third of six stops
  TempDir dir;
  HeatmapPlot p;
  p.xs = {1, 2, 3};
  p.ys = {10, 20};
  p.z = {1, 2, nan, 4, 5, 6};
  p.empty_label = "grey: nothing ran";
  const auto cells = heatmap_cells(p, 1, 6);
  ASSERT_EQ(cells.size(), 6u);
  EXPECT_EQ(cells[2].colour, empty_cell_colour);
  EXPECT_EQ(cells[5].x0, 2.5);
  EXPECT_EQ(cells[5].y1, 25);
  const RenderReport r = render(p, dir.file("h.png"), {320, 240});
  EXPECT_EQ(r.cells, 6u);
  EXPECT_EQ(r.empty_cells, 1u);
  EXPECT_TRUE(r.empty_note);
  p.z[2] = 3;  // no empty cell: no note
  EXPECT_FALSE(render(p, dir.file("h.png"), {320, 240}).empty_note);
}

TEST(PlotStyle, TheMarkIsARedDotWithItsLabelOffTheCurveAndInsideTheFrame) {
  TempDir dir;
  // A rising curve through the mark: a label right of the point would sit on it.
  LinePlot p;
  p.series.push_back({"", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}});
  p.mark = PlotMark{5, 5, "(0.5, 0.25): 50%"};
  const RenderReport r = render(p, dir.file("m.png"), {320, 240});
  EXPECT_EQ(r.mark_style, "r#o");
  EXPECT_NE(r.label_side, LabelSide::right);
  EXPECT_NE(r.label_side, LabelSide::automatic);
  // The chosen box crosses none of the curve.
  const std::vector<std::vector<std::pair<double, double>>> diagonal{{{0, 0}, {1, 1}}};
  EXPECT_EQ(choose_label_side(0.5, 0.5, 16, 1, diagonal), r.label_side);
  const LabelBox b = place_label(r.label_side, 0.5, 0.5, 16, 1);
  EXPECT_TRUE(b.x1 < b.y0 || b.x0 > b.y1) << to_string(r.label_side);  // wholly on one side of y = x
  // Near the right edge a long label goes left, inside the frame.
  const LabelSide edge = choose_label_side(0.9, 0.5, 30, 1, {});
  const LabelBox e = place_label(edge, 0.9, 0.5, 30, 1);
  EXPECT_GE(e.x0, 0);
  EXPECT_LE(e.x1, 1);
  // A side given is kept.
  p.mark->side = LabelSide::above_left;
  EXPECT_EQ(render(p, dir.file("m.png"), {320, 240}).label_side, LabelSide::above_left);
}

// Pixels of a PNG that are clearly red (the mark; no default pen is red
// for a single blue line).
std::size_t red_pixels(const std::string& path) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) return 0;
  img.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, px.data(), 0, nullptr)) return 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < px.size(); i += 3) n += px[i] > 200 && px[i + 1] < 60 && px[i + 2] < 60;
  return n;
}

TEST(PlotStyle, TheMarkIsDrawnRedInTheImage) {
  TempDir dir;
  LinePlot p;
  p.series.push_back({"", {0, 10}, {0, 10}});
  render(p, dir.file("plain.png"), {320, 240});
  EXPECT_EQ(red_pixels(dir.file("plain.png")), 0u);
  p.mark = PlotMark{5, 5, "here"};
  render(p, dir.file("marked.png"), {320, 240});
  EXPECT_GT(red_pixels(dir.file("marked.png")), 4u);  // a dot of a few pixels at this size
}

TEST(PlotStyle, MarkLabelSidesParseByNameAndOthersAreRefused) {
  for (int i = 0; i <= int(LabelSide::below_left); ++i)
    EXPECT_EQ(parse_label_side(to_string(LabelSide(i))), LabelSide(i));
  try {
    parse_label_side("sideways");
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("--mark-label 'sideways': expected one of automatic, right,"),
              std::string::npos)
        << e.what();
  }
  const auto r = test::run_chaosweep("figure cheb_lyapunov --mark-label up -o /nonexistent/x.png");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--mark-label 'up'"), std::string::npos) << r.err;
}

TEST(Grouping, TextKeysComeInNaturalOrder) {
  EXPECT_TRUE(natural_less("2", "12"));
  EXPECT_FALSE(natural_less("12", "2"));
  EXPECT_TRUE(natural_less("run 2, b", "run 12, a"));
  EXPECT_TRUE(natural_less("a", "b"));
  EXPECT_TRUE(natural_less("a", "a1"));
  EXPECT_FALSE(natural_less("a7", "a7"));
  EXPECT_TRUE(natural_less("x9y", "x10"));
  const ResultSet rs =
      ResultSet::from_columns({{"v", {1, 2, 3, 4, 5}}}, {{"label", {"12", "2", "1", "13", "case 10"}}});
  std::vector<std::string> order;
  for (const Group& g : group_rows(rs, {"label"}, all_rows(rs))) order.push_back(g.key[0]);
  EXPECT_EQ(order, (std::vector<std::string>{"1", "2", "12", "13", "case 10"}));
}

TEST(ColumnLabels, AxesNameTheMeaningAndUnitOfEveryMeasuredColumn) {
  EXPECT_EQ(axis_label("coverage_time"), "coverage time (s)");
  EXPECT_EQ(axis_label("c3_n"), "c3_n: RK2 steps of the trajectory");
  EXPECT_EQ(axis_label("v"), "v: robot speed (m/s)");
  EXPECT_EQ(axis_label("A"), "A: Arnold coefficient");
  EXPECT_EQ(axis_label("no_such_column"), "no_such_column");
  // Every measured numeric column the store writes reads as more than its
  // raw name; a parameter's label starts with its name; all fit an axis.
  for (const Column& c : result_columns()) {
    if (c.type == Column::Type::text || c.name == "param_hash") continue;
    const std::string l = axis_label(c.name);
    if (find_param(c.name)) {
      EXPECT_EQ(l.rfind(c.name, 0), 0u) << l;
    } else {
      EXPECT_NE(l, c.name);
    }
    EXPECT_LE(l.size(), 48u) << l;
  }
}

// Two result files of one planner pair: per label, ok coverage times and timeouts.
class TwoResultSets : public ::testing::Test {
 protected:
  void SetUp() override {
    write("a/results.h5", {{"x", 100}, {"x", 300}, {"x", 200}, {"x", nan}, {"y", 50}});
    write("b/results.h5", {{"x", 150}, {"x", nan}, {"y", nan}, {"y", 80}});
    opt_.size = {320, 240};
  }
  void write(const std::string& name, const std::vector<std::pair<std::string, double>>& runs) {
    std::filesystem::create_directories(std::filesystem::path(dir_.file(name)).parent_path());
    std::vector<RunRow> rows;
    for (const auto& [label, ct] : runs) {
      RunRow r;
      r.tuple.run_id = std::int64_t(rows.size());
      r.tuple.env_spec = "empty";
      r.tuple.label = label;
      r.result.status = std::isnan(ct) ? Status::timeout : Status::ok;
      r.result.coverage_time = ct;
      rows.push_back(r);
    }
    H5RunWriter w(dir_.file(name));
    w.append(rows);
    w.finish();
  }
  std::vector<std::string> files() const { return {dir_.file("a/results.h5"), dir_.file("b/results.h5")}; }
  TempDir dir_;
  FigureOptions opt_;
};

TEST_F(TwoResultSets, FileLabelsAreTheShortestDistinctNames) {
  EXPECT_EQ(file_labels({"out/a.h5", "out/b.h5"}), (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(file_labels({"out/a/results.h5", "out/b/results.h5"}),
            (std::vector<std::string>{"a/results", "b/results"}));
  EXPECT_EQ(file_labels({"x/a/r.h5", "y/a/r.h5"}), (std::vector<std::string>{"x/a/r.h5", "y/a/r.h5"}));
}

TEST_F(TwoResultSets, CtDistributionCsvHoldsEachCurvesStepsUpToItsOkShare) {
  opt_.by = "label";
  const FigureOutput out = make_per_file_figure("ct_distribution", files(), {}, opt_, dir_.file("ct.png"));
  // Groups in order, a file after b within each; a curve's last share is its ok share.
  EXPECT_EQ(test::read_file(out.csv),
            "label,label,runs,ok,not_ok_share,coverage_time,cumulative_share\n"
            "x,a/results,4,3,0.25,100,0.25\n"
            "x,a/results,4,3,0.25,200,0.5\n"
            "x,a/results,4,3,0.25,300,0.75\n"
            "x,b/results,2,1,0.5,150,0.5\n"
            "y,a/results,1,1,0,50,1\n"
            "y,b/results,2,1,0.5,80,0.5\n");
  ASSERT_EQ(out.lines.size(), 4u);
  EXPECT_EQ(out.lines[0], "a/results: label x (3/4 ok): 75.0% reached the target, median CT 200 s");
  EXPECT_TRUE(std::filesystem::exists(out.image));
  // --where applies to each file.
  const FigureOutput only_y = make_per_file_figure("ct_distribution", files(), {"label=y"}, opt_, dir_.file("y.png"));
  EXPECT_EQ(only_y.lines.size(), 2u);
}

TEST_F(TwoResultSets, CtDistributionRefusesTooManyCurvesAndFilesWithoutOkRuns) {
  opt_.by = "run_id";  // 5 + 4 curves
  EXPECT_NO_THROW(make_per_file_figure("ct_distribution", files(), {}, opt_, dir_.file("ok.png")));
  write("c.h5", {{"x", 1}, {"x", 2}, {"x", 3}, {"x", 4}});
  auto all = files();
  all.push_back(dir_.file("c.h5"));
  try {
    make_per_file_figure("ct_distribution", all, {}, opt_, dir_.file("many.png"));
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("13 curves"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 12"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_.file("many.png")));
  write("none.h5", {{"x", nan}, {"y", nan}});
  opt_.by = "";
  try {
    make_per_file_figure("ct_distribution", {dir_.file("none.h5")}, {}, opt_, dir_.file("none.png"));
    FAIL() << "no error";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("no run in none reached the target"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_per_file_figure("fig6a", files(), {}, opt_, dir_.file("f.png")), AnalysisError);
}

TEST_F(TwoResultSets, CommandLineDrawsCtDistributionOfSeveralFiles) {
  auto r = test::run_chaosweep("figure ct_distribution " + files()[0] + " " + files()[1] + " --by label -o " +
                               dir_.file("cli.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("b/results: label y (1/2 ok): 50.0% reached the target"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir_.file("cli.csv")));
  r = test::run_chaosweep("figure ct_distribution " + files()[0] + " --by colour -o " + dir_.file("bad.png"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no column 'colour'"), std::string::npos) << r.err;
}

// figure leaderboard: per planner, in the leaderboard's overall order, the
// share of its runs over every map within each PR; its CSV holds one row per
// ok run, a planner with none one row with PR "-".
TEST(Figures, LeaderboardDrawsEachPlannersShareOfRunsWithinAPrInRankOrder) {
  TempDir dir;
  const std::vector<std::string> label{"slow", "slow", "fast", "fast", "never", "slow", "fast", "never"};
  const std::vector<std::string> status{"ok", "ok", "ok", "ok", "timeout", "ok", "ok", "timeout"};
  const std::vector<std::string> env{"A", "A", "A", "A", "A", "B", "B", "B"};
  const double n = std::numeric_limits<double>::quiet_NaN();
  const ResultSet rs = ResultSet::from_columns({{"coverage_time", {400, 600, 100, 300, n, 900, 200, n}},
                                                {"pr", {4, 6, 1, 3, n, 9, 2, n}},
                                                {"size_x", std::vector<double>(8, 50)},
                                                {"size_y", std::vector<double>(8, 50)},
                                                {"sr", std::vector<double>(8, 1)}},
                                               {{"label", label}, {"status", status}, {"env", env}});
  FigureOptions opt;
  const FigureOutput out = make_figure("leaderboard", rs, opt, dir.file("lb.png"));
  ASSERT_EQ(out.lines.size(), 3u);
  EXPECT_EQ(out.lines[0], "fast: mean rank 1 over 2 map(s), 100.0% of 3 runs reached the target, median PR of those 2");
  EXPECT_EQ(out.lines[1], "slow: mean rank 2 over 2 map(s), 100.0% of 3 runs reached the target, median PR of those 6");
  EXPECT_EQ(out.lines[2], "never: mean rank 3 over 2 map(s), 0.0% of 2 runs reached the target");
  EXPECT_TRUE(std::filesystem::file_size(dir.file("lb.png")) > 0);
  std::ifstream csv(dir.file("lb.csv"));
  std::stringstream text;
  text << csv.rdbuf();
  EXPECT_EQ(text.str(),
            "planner,mean_rank,runs,ok,pr,cumulative_share\n"
            "fast,1,3,3,1,0.3333333333333333\n"
            "fast,1,3,3,2,0.6666666666666666\n"
            "fast,1,3,3,3,1\n"
            "slow,2,3,3,4,0.3333333333333333\n"
            "slow,2,3,3,6,0.6666666666666666\n"
            "slow,2,3,3,9,1\n"
            "never,3,2,0,-,0\n");
  // No run reached the target: nothing to draw, said so.
  const ResultSet none = rs.where({"label=never"});
  try {
    make_figure("leaderboard", none, opt, dir.file("none.png"));
    FAIL() << "no ok run drawn";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("no run reached the target"), std::string::npos) << e.what();
  }
}

TEST(PlotStyle, ALogXAxisNeedsPositiveValuesAndTakesNoMark) {
  TempDir dir;
  LinePlot p;
  p.x_log = true;
  p.series.push_back({"a", {1, 10, 100}, {0, 50, 100}});
  p.series.push_back({"b", {2, 20, 200}, {0, 50, 100}});
  EXPECT_TRUE(render(p, dir.file("log.png"), {320, 240}).legend_outside);
  p.series[0].x[0] = 0;
  EXPECT_THROW(render(p, dir.file("zero.png"), {320, 240}), AnalysisError);
  p.series[0].x[0] = 1;
  p.mark = PlotMark{10, 50, "m"};
  EXPECT_THROW(render(p, dir.file("mark.png"), {320, 240}), AnalysisError);
}

}  // namespace
}  // namespace chaosweep
