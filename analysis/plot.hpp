#pragma once
// Figure descriptions (pure data) and their rendering with MathGL. Figures
// build these from results; only plot.cpp knows MathGL.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace chaosweep {

struct PlotMark {
  double x, y;
  std::string label;  // printed beside the marker
};

// A colour map of z over a rectangular grid of axis values (NaN: no data,
// left blank).
struct HeatmapPlot {
  std::string title, xlabel, ylabel, zlabel;
  std::vector<double> xs, ys;  // increasing
  std::vector<double> z;       // z[j * xs.size() + i]
  std::optional<PlotMark> mark;
};

struct LineSeries {
  std::string name;
  std::vector<double> x, y;
};

struct LinePlot {
  std::string title, xlabel, ylabel;
  std::vector<LineSeries> series;
  std::optional<PlotMark> mark;
  std::optional<std::pair<double, double>> y_range;
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

// Writes the figure to `path`; the format follows the extension: .png, .svg,
// .pdf or .eps (AnalysisError naming the allowed ones otherwise). The file
// appears complete or not at all (written aside, then renamed).
void render(const HeatmapPlot& p, const std::string& path, ImageSize size);
void render(const LinePlot& p, const std::string& path, ImageSize size);
void render(const MapPlot& p, const std::string& path, ImageSize size);

// The formats render() accepts, for messages and checks before work starts.
void check_image_path(const std::string& path);

}  // namespace chaosweep
