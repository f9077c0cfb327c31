#pragma once
// Figure descriptions (pure data) and their rendering with MathGL. Figures
// build these from results; only plot.cpp knows MathGL.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/plot_style.hpp"

namespace chaosweep {

// A red dot with a label beside it; `automatic` puts the label where it
// stays inside the frame and crosses the fewest lines.
struct PlotMark {
  double x, y;
  std::string label;  // printed beside the marker
  LabelSide side = LabelSide::automatic;
};

// A colour map of z over a rectangular grid of axis values: one flat cell
// per value (no interpolation); NaN cells grey, explained by empty_label.
struct HeatmapPlot {
  std::string title, xlabel, ylabel, zlabel;
  std::vector<double> xs, ys;  // increasing
  std::vector<double> z;       // z[j * xs.size() + i]
  std::optional<PlotMark> mark;
  std::string empty_label = "grey: no data";  // printed under the plot when a cell is NaN
};

// colour, dash: indices for line_pen (plot_style.hpp); -1: by position.
struct LineSeries {
  std::string name;
  std::vector<double> x, y;
  int colour = -1, dash = -1;
};

struct LinePlot {
  std::string title, xlabel, ylabel;
  std::vector<LineSeries> series;
  std::optional<PlotMark> mark;
  std::optional<std::pair<double, double>> y_range;
  bool x_log = false;  // a log10 x axis (every x > 0; no mark)
};

struct Box2 {
  double x0, y0, x1, y1;
};

// A run over its map: covered cells, obstacles, the path (Arnold segments and
// transits apart), zone midpoints, start and end.
struct MapPlot {
  std::string title;
  double lx = 0, ly = 0;
  double cell = 1;
  int nx = 0, ny = 0;
  std::vector<unsigned char> covered;  // covered[j * nx + i]
  std::vector<Box2> obstacles;
  std::vector<std::vector<std::pair<double, double>>> arnold_paths, transit_paths;
  std::vector<std::pair<double, double>> zone_midpoints;
  std::vector<std::pair<double, double>> subgoals;  // Chebyshev planner
  std::vector<Box2> regions, transitions;           // its free-space decomposition
  std::pair<double, double> start{0, 0}, end{0, 0};
};

struct ImageSize {
  int width = 800, height = 600;
};
// "WIDTHxHEIGHT" (each 100..8000); throws AnalysisError naming --size.
ImageSize parse_image_size(const std::string& s);

// What render() drew, for tests: cells (and the empty ones among them), the
// lines' pens, the mark's style and its label's side, the legend's place.
struct RenderReport {
  std::size_t cells = 0, empty_cells = 0;
  bool empty_note = false;  // empty_label printed
  std::vector<std::string> pens;
  std::string mark_style;
  LabelSide label_side = LabelSide::automatic;
  bool legend_outside = false;
};

// Writes the figure to `path`; the format follows the extension: .png, .svg,
// .pdf or .eps (AnalysisError naming the allowed ones otherwise). The file
// appears complete or not at all (written aside, then renamed).
RenderReport render(const HeatmapPlot& p, const std::string& path, ImageSize size);
RenderReport render(const LinePlot& p, const std::string& path, ImageSize size);
void render(const MapPlot& p, const std::string& path, ImageSize size);

// The formats render() accepts, for messages and checks before work starts.
void check_image_path(const std::string& path);

}  // namespace chaosweep
