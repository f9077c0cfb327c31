#pragma once
// The choices render() makes that can be checked without looking: pens for
// many lines, heatmap cells and their colours, where a mark's label goes,
// how much room the legend takes. Pure functions, no MathGL.
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace chaosweep {

struct HeatmapPlot;
struct LinePlot;

// Where a mark's label sits relative to its point.
enum class LabelSide { automatic, right, left, above, below, above_right, below_right, above_left, below_left };
const char* to_string(LabelSide s);
// "automatic", "right", ..., "below_left"; throws AnalysisError naming --mark-label and the allowed names.
LabelSide parse_label_side(const std::string& s);

// 8 colours x 6 dash styles: distinct pens for up to line_style_count lines;
// beyond that they repeat (a legend of more lines is unreadable anyway).
constexpr std::size_t line_colour_count = 8, line_dash_count = 6;
constexpr std::size_t line_style_count = line_colour_count * line_dash_count;
// MathGL pen of colour c and dash d (each taken modulo its count), width 2.
std::string line_pen(std::size_t colour, std::size_t dash);
// The k-th line's pen: the colours first, then the next dash style.
std::string series_pen(std::size_t k);

// A heatmap cell as drawn: one flat rectangle per grid value, centred on the
// axis values, edges halfway to the neighbours (no interpolation).
struct HeatCell {
  double x0, y0, x1, y1;
  double z;            // NaN: empty
  std::string colour;  // MathGL "{xRRGGBB}"
};
std::vector<HeatCell> heatmap_cells(const HeatmapPlot& p, double zlo, double zhi);
// Edges of cells centred on increasing axis values.
std::vector<double> cell_edges(const std::vector<double>& centres);
// The colour of t in [0, 1] on MathGL's "BbcyrR" scheme (the colour bar's).
std::string heat_colour(double t);
inline const char* empty_cell_colour = "{xC0C0C0}";

// A label box in axis fractions ([0, 1] over each axis' range).
struct LabelBox {
  double x0, y0, x1, y1;
};
// The label's box for a side, for a point at (fx, fy) in axis fractions;
// `chars` long, `scale` the font relative to a full-width plot.
LabelBox label_box(LabelSide side, double fx, double fy, std::size_t chars, double scale);
// The box as drawn: above or below (and the corners) slide sideways to stay
// inside the frame; left and right stay put.
LabelBox place_label(LabelSide side, double fx, double fy, std::size_t chars, double scale);
// The side whose box (as placed) lies inside the frame and crosses the fewest points of
// the plotted lines (ties: the first in the order right, below_right,
// above_left, left, ...). `lines` in axis fractions.
LabelSide choose_label_side(double fx, double fy, std::size_t chars, double scale,
                            const std::vector<std::vector<std::pair<double, double>>>& lines);

// A legend right of the plot, drawn in the plot's own coordinates beyond
// its right edge: columns of rows, filled column by column.
struct LegendLayout {
  double plot_width = 1;    // share of the canvas width for the plot and its legend's MultiPlot cell
  double text_size = -0.7;  // MathGL Puts size
  std::size_t rows = 0, columns = 0;
  double row = 0;           // row step, share of the axes' height
  double column_width = 0;  // share of the axes' width
  double sample = 0;        // the line sample's length, share of the axes' width
  double offset = 0;        // from the axes' right edge to the legend, share of the axes' width
};
LegendLayout legend_layout(std::size_t entries, std::size_t longest_chars);
// The font relative to a plot that keeps `plot_width` of the canvas width
// (1 for the full-width plot).
double plot_font_scale(double plot_width);

}  // namespace chaosweep
