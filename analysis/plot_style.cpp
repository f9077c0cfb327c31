#include "analysis/plot_style.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "analysis/plot.hpp"
#include "analysis/result_set.hpp"

namespace chaosweep {

const char* to_string(LabelSide s) {
  switch (s) {
    case LabelSide::automatic:
      return "automatic";
    case LabelSide::right:
      return "right";
    case LabelSide::left:
      return "left";
    case LabelSide::above:
      return "above";
    case LabelSide::below:
      return "below";
    case LabelSide::above_right:
      return "above_right";
    case LabelSide::below_right:
      return "below_right";
    case LabelSide::above_left:
      return "above_left";
    case LabelSide::below_left:
      return "below_left";
  }
  return "?";
}

LabelSide parse_label_side(const std::string& s) {
  std::string names;
  for (int i = 0; i <= int(LabelSide::below_left); ++i) {
    const auto side = LabelSide(i);
    if (s == to_string(side)) return side;
    names += (i ? ", " : "") + std::string(to_string(side));
  }
  throw AnalysisError("--mark-label '" + s + "': expected one of " + names);
}

std::string line_pen(std::size_t colour, std::size_t dash) {
  // Colours far apart first; dashes: solid, long, medium, small, dash-dot, dots.
  static constexpr std::array<char, line_colour_count> colours{'b', 'r', 'g', 'k', 'm', 'c', 'q', 'u'};
  static constexpr std::array<char, line_dash_count> dashes{'-', '|', ';', '=', 'j', ':'};
  return {colours[colour % line_colour_count], dashes[dash % line_dash_count], '2'};
}

std::string series_pen(std::size_t k) { return line_pen(k % line_colour_count, k / line_colour_count); }

std::vector<double> cell_edges(const std::vector<double>& c) {
  std::vector<double> e(c.size() + 1);
  if (c.empty()) return {};
  if (c.size() == 1) {
    const double h = c[0] == 0 ? 0.5 : std::fabs(c[0]) * 0.05;
    return {c[0] - h, c[0] + h};
  }
  for (std::size_t i = 1; i < c.size(); ++i) e[i] = 0.5 * (c[i - 1] + c[i]);
  e.front() = c.front() - (e[1] - c.front());
  e.back() = c.back() + (c.back() - e[c.size() - 1]);
  return e;
}

std::string heat_colour(double t) {
  // "BbcyrR": dark blue, blue, cyan, yellow, red, dark red, evenly spaced.
  static constexpr double stops[6][3] = {{0, 0, 0.5}, {0, 0, 1}, {0, 1, 1}, {1, 1, 0}, {1, 0, 0}, {0.5, 0, 0}};
  t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * 5.0;
  const int i = std::min(4, int(t));
  const double f = t - i;
  char buf[16];
  int rgb[3];
  for (int k = 0; k < 3; ++k) rgb[k] = int(std::lround(255.0 * (stops[i][k] + f * (stops[i + 1][k] - stops[i][k]))));
  std::snprintf(buf, sizeof buf, "{x%02X%02X%02X}", rgb[0], rgb[1], rgb[2]);
  return buf;
}

std::vector<HeatCell> heatmap_cells(const HeatmapPlot& p, double zlo, double zhi) {
  const std::vector<double> ex = cell_edges(p.xs), ey = cell_edges(p.ys);
  std::vector<HeatCell> out;
  const double span = zhi > zlo ? zhi - zlo : 1.0;
  for (std::size_t j = 0; j < p.ys.size(); ++j)
    for (std::size_t i = 0; i < p.xs.size(); ++i) {
      const double z = p.z[j * p.xs.size() + i];
      out.push_back(
          {ex[i], ey[j], ex[i + 1], ey[j + 1], z, std::isnan(z) ? empty_cell_colour : heat_colour((z - zlo) / span)});
    }
  return out;
}

namespace {

// A character's width and the text's height in axis fractions of a plot
// spanning the canvas (MathGL's font at the sizes plot.cpp uses).
constexpr double char_width = 0.0165, text_height = 0.055, gap = 0.02;

}  // namespace

LabelBox label_box(LabelSide side, double fx, double fy, std::size_t chars, double scale) {
  const double w = char_width * scale * double(chars), h = text_height * scale;
  double x0 = fx + gap, y0 = fy - h / 2;  // right
  switch (side) {
    case LabelSide::automatic:
    case LabelSide::right:
      break;
    case LabelSide::left:
      x0 = fx - gap - w;
      break;
    case LabelSide::above:
      x0 = fx - w / 2, y0 = fy + gap;
      break;
    case LabelSide::below:
      x0 = fx - w / 2, y0 = fy - gap - h;
      break;
    case LabelSide::above_right:
      y0 = fy + gap;
      break;
    case LabelSide::below_right:
      y0 = fy - gap - h;
      break;
    case LabelSide::above_left:
      x0 = fx - gap - w, y0 = fy + gap;
      break;
    case LabelSide::below_left:
      x0 = fx - gap - w, y0 = fy - gap - h;
      break;
  }
  return {x0, y0, x0 + w, y0 + h};
}

namespace {

// The box slid sideways into the frame where it sticks out (the label then
// still starts or ends near its point).
LabelBox slid_inside(LabelBox b) {
  const double w = b.x1 - b.x0;
  if (b.x0 < 0) b.x0 = 0, b.x1 = w;
  if (b.x1 > 1) b.x1 = 1, b.x0 = 1 - w;
  return b;
}

}  // namespace

LabelBox place_label(LabelSide side, double fx, double fy, std::size_t chars, double scale) {
  LabelBox b = label_box(side, fx, fy, chars, scale);
  const bool vertical_only = side != LabelSide::left && side != LabelSide::right;
  return vertical_only ? slid_inside(b) : b;
}

LabelSide choose_label_side(double fx, double fy, std::size_t chars, double scale,
                            const std::vector<std::vector<std::pair<double, double>>>& lines) {
  static constexpr LabelSide order[] = {LabelSide::right, LabelSide::below_right, LabelSide::above_left,
                                        LabelSide::left,  LabelSide::above_right, LabelSide::below_left,
                                        LabelSide::above, LabelSide::below};
  LabelSide best = LabelSide::right;
  long best_hits = -1;
  bool best_inside = false;
  for (LabelSide s : order) {
    const LabelBox b = place_label(s, fx, fy, chars, scale);
    const bool inside = b.x0 >= 0 && b.x1 <= 1 && b.y0 >= 0 && b.y1 <= 1;
    long hits = 0;  // points along every segment (sampled finely) inside the box
    for (const auto& line : lines)
      for (std::size_t i = 0; i + 1 < line.size(); ++i)
        for (int k = 0; k <= 50; ++k) {
          const double t = k / 50.0;
          const double x = line[i].first + t * (line[i + 1].first - line[i].first);
          const double y = line[i].second + t * (line[i + 1].second - line[i].second);
          constexpr double m = 0.015;  // a little clear space around the text
          hits += x >= b.x0 - m && x <= b.x1 + m && y >= b.y0 - m && y <= b.y1 + m;
        }
    if (best_hits < 0 || (inside && !best_inside) || (inside == best_inside && hits < best_hits))
      best = s, best_hits = hits, best_inside = inside;
  }
  return best;
}

LegendLayout legend_layout(std::size_t entries, std::size_t longest_chars) {
  // In pixels of an 800x600 canvas (MathGL scales text with the canvas): a
  // character is about 10 x |size| wide, a row 28 x |size| high; the axes
  // are about 375 high and lose about 130 of the width to their margins.
  LegendLayout l;
  if (entries == 0) return l;
  constexpr double axes_height = 375, margins = 130, canvas = 800;
  l.text_size = entries <= 2 * 19 ? -0.7 : -0.55;
  const double row_px = 28.0 * -l.text_size, char_px = 10.1 * -l.text_size;
  const auto rows_fit = std::size_t(axes_height / row_px);
  l.columns = (entries + rows_fit - 1) / rows_fit;
  l.rows = (entries + l.columns - 1) / l.columns;
  const double sample_px = 36, gap_px = 12, offset_px = 14;
  const double column_px = sample_px + 2 * gap_px + double(longest_chars) * char_px;
  const double legend_px = offset_px + double(l.columns) * column_px;
  l.plot_width = std::clamp((canvas - legend_px - 10) / canvas, 0.45, 0.9);
  const double axes_px = l.plot_width * canvas - margins;
  l.row = row_px / axes_height;
  l.column_width = column_px / axes_px;
  l.sample = sample_px / axes_px;
  l.offset = offset_px / axes_px;
  return l;
}

double plot_font_scale(double plot_width) {
  // The full-width plot's axes span about 0.64 of the canvas; a narrower
  // subplot loses about 0.16 to its margins.
  return 0.64 / std::max(0.1, plot_width - 0.16);
}

}  // namespace chaosweep
