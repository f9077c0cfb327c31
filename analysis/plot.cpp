#include "analysis/plot.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "analysis/mathgl.hpp"
#include "analysis/result_set.hpp"

namespace chaosweep {

namespace fs = std::filesystem;
using mathgl::Data;
using mathgl::Graph;

namespace {

std::string extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// MathGL reads TeX-like markup: keep user text literal.
std::string literal(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '_' || c == '^' || c == '\\' || c == '{' || c == '}') out += '\\';
    out += c;
  }
  return out;
}

// Saves in the format of the path's extension, aside first, then renamed.
void save(Graph& gr, const std::string& path) {
  check_image_path(path);
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const std::string ext = extension(path);
  std::string hidden = target.stem().string();
  hidden.insert(0, 1, '.');
  hidden.append(".partial");
  const std::string stem = (target.parent_path() / hidden).string();
  std::string written;
  if (ext == ".png") {
    written = stem + ".png";
    gr.WritePNGSolid(written.c_str(), "");
  } else if (ext == ".svg") {
    written = stem + ".svg";
    gr.WriteSVG(written.c_str(), "");
  } else if (ext == ".eps") {
    written = stem + ".eps";
    gr.WriteEPS(written.c_str(), "");
  } else {  // .pdf: MathGL writes NAME.prc and, from it, NAME.pdf
    gr.WritePRC((stem + ".prc").c_str(), "", true);
    fs::remove(stem + ".prc");
    written = stem + ".pdf";
  }
  std::error_code ec;
  if (!fs::exists(written, ec) || fs::file_size(written, ec) == 0)
    throw AnalysisError("could not write " + path + " (MathGL wrote nothing)");
  fs::rename(written, target);
}

std::pair<double, double> padded(double lo, double hi) {
  if (!(hi > lo)) {
    const double d = lo == 0 ? 1.0 : std::fabs(lo) * 0.05;
    return {lo - d, hi + d};
  }
  return {lo, hi};
}

void frame(Graph& gr, const std::string& title, const std::string& xlabel, const std::string& ylabel) {
  gr.SetFontSize(3.2);
  if (!title.empty()) gr.Title(literal(title).c_str(), "", title.size() > 40 ? -1.1 : -1.4);
  gr.Box();
  gr.Axis("xy");
  // Long labels (a column's meaning and unit) smaller, to fit beside the axis.
  gr.Label('x', literal(xlabel).c_str(), 0, xlabel.size() > 30 ? "size -0.8" : "");
  gr.Label('y', literal(ylabel).c_str(), 0, ylabel.size() > 20 ? "size -0.75" : "");
}

struct Frame {
  double x0, x1, y0, y1;
  double fx(double x) const { return (x - x0) / (x1 - x0); }
  double fy(double y) const { return (y - y0) / (y1 - y0); }
};

constexpr const char* mark_style = "r#o";  // a filled red dot, as in the papers

// The mark and its label on the side given (automatic: chosen by the caller);
// `pad` puts a white box behind the label (over a colour map). z lifts both
// above the faces (MathGL hides what lies below).
void put_mark(Graph& gr, const PlotMark& m, LabelSide side, const Frame& f, double scale, bool pad, RenderReport& rep) {
  gr.Mark(mglPoint(m.x, m.y, 0.8), mark_style);
  rep.mark_style = mark_style;
  rep.label_side = side;
  if (m.label.empty()) return;
  const LabelBox b = place_label(side, f.fx(m.x), f.fy(m.y), m.label.size(), scale);
  const double bx0 = f.x0 + b.x0 * (f.x1 - f.x0), bx1 = f.x0 + b.x1 * (f.x1 - f.x0);
  const double by0 = f.y0 + b.y0 * (f.y1 - f.y0), by1 = f.y0 + b.y1 * (f.y1 - f.y0);
  if (pad) gr.FaceZ(mglPoint(bx0, by0, 0.6), bx1 - bx0, by1 - by0, "w");
  gr.Puts(mglPoint(bx0, by0 + 0.15 * (by1 - by0), 0.9), literal(m.label).c_str(), ":L", -0.8);
}

struct LegendEntry {
  std::string name, pen;
  bool marker = false;  // drawn as a mark, not a line sample
};

// The legend right of the axes, in the plot's coordinates beyond its edge
// (MathGL's own legend stays inside the axes, over the data).
void outside_legend(Graph& gr, const Frame& f, const std::vector<LegendEntry>& entries, const LegendLayout& l,
                    double z) {
  gr.SetCut(false);
  const double w = f.x1 - f.x0, h = f.y1 - f.y0;
  const double text_h = 0.045 * -l.text_size / 0.8;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const std::size_t c = k / l.rows, r = k % l.rows;
    const double x = f.x1 + (l.offset + double(c) * l.column_width) * w;
    const double y = f.y1 - (double(r) + 0.5) * l.row * h;
    const LegendEntry& e = entries[k];
    if (e.marker) {
      gr.Mark(mglPoint(x + 0.5 * l.sample * w, y, z), e.pen.c_str());
    } else {
      gr.Line(mglPoint(x, y, z), mglPoint(x + l.sample * w, y, z), e.pen.c_str());
    }
    gr.Puts(mglPoint(x + 1.3 * l.sample * w, y - 0.4 * text_h * h, z), literal(e.name).c_str(), ":L", l.text_size);
  }
}

// A title over the whole canvas, then the plot's cell of `share` of the width.
void title_and_cell(Graph& gr, const std::string& title, double share) {
  gr.SetFontSize(3.2);
  // At a fixed place on the canvas (":A"): Title() beside a MultiPlot cell
  // clipped the top of the text.
  // About 54 characters fit 800 px at 600 px high; the font grows with the
  // smaller side of the canvas.
  const double w = gr.GetWidth(), h = gr.GetHeight();
  const double fit = 54.0 * (w / 800.0) * (600.0 / std::min(w, h));
  if (!title.empty())
    gr.Puts(0.5, 0.94, literal(title).c_str(), ":AC", -1.2 * std::min(1.0, fit / double(title.size())));
  gr.MultiPlot(100, 1, 0, int(share * 100), 1, "<_^");
}

}  // namespace

void check_image_path(const std::string& path) {
  const std::string ext = extension(path);
  if (ext != ".png" && ext != ".svg" && ext != ".pdf" && ext != ".eps")
    throw AnalysisError("-o " + path + ": unknown image format '" + ext + "' (allowed: .png, .svg, .pdf, .eps)");
}

ImageSize parse_image_size(const std::string& s) {
  ImageSize z;
  char x = 0;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &z.width, &x, &z.height, &tail) != 3 || x != 'x' || z.width < 100 ||
      z.width > 8000 || z.height < 100 || z.height > 8000)
    throw AnalysisError("--size " + s + ": expected WIDTHxHEIGHT, each in [100, 8000] pixels");
  return z;
}

RenderReport render(const HeatmapPlot& p, const std::string& path, ImageSize size) {
  const long nx = long(p.xs.size()), ny = long(p.ys.size());
  if (nx < 1 || ny < 1 || p.z.size() != std::size_t(nx * ny)) throw AnalysisError("heatmap: no data to draw");
  RenderReport rep;
  Graph gr(size.width, size.height);
  double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
  for (double v : p.z)
    if (!std::isnan(v)) zlo = std::min(zlo, v), zhi = std::max(zhi, v);
  if (!(zhi >= zlo)) zlo = 0, zhi = 1;  // every cell empty
  const auto [c0, c1] = padded(zlo, zhi);
  // One flat face per cell, its colour the colour bar's at its value: the
  // cell-to-cell jumps stay visible and square cells stay square.
  const std::vector<HeatCell> cells = heatmap_cells(p, c0, c1);
  const Frame f{cells.front().x0, cells.back().x1, cells.front().y0, cells.back().y1};
  gr.SetRanges(f.x0, f.x1, f.y0, f.y1, -1, 1);
  gr.SetRange('c', c0, c1);
  frame(gr, p.title, p.xlabel, p.ylabel);
  for (const HeatCell& c : cells) {
    gr.FaceZ(mglPoint(c.x0, c.y0, -0.5), c.x1 - c.x0, c.y1 - c.y0, c.colour.c_str());
    ++rep.cells;
    rep.empty_cells += std::isnan(c.z);
  }
  gr.Box();  // the frame over the cells' edges
  gr.Colorbar("BbcyrR>");
  gr.Puts(mglPoint(f.x1 + (f.x1 - f.x0) * 0.16, f.y1 + (f.y1 - f.y0) * 0.06), literal(p.zlabel).c_str(), ":C", -0.9);
  if (rep.empty_cells > 0 && !p.empty_label.empty()) {
    gr.Puts(mglPoint(f.x0 - (f.x1 - f.x0) * 0.12, f.y0 - (f.y1 - f.y0) * 0.24, 0.9), literal(p.empty_label).c_str(),
            ":L", -0.8);
    rep.empty_note = true;
  }
  if (p.mark) {
    LabelSide side = p.mark->side;
    if (side == LabelSide::automatic)
      side = choose_label_side(f.fx(p.mark->x), f.fy(p.mark->y), p.mark->label.size(), 1.0, {});
    put_mark(gr, *p.mark, side, f, 1.0, true, rep);
  }
  save(gr, path);
  return rep;
}

RenderReport render(const LinePlot& p, const std::string& path, ImageSize size) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const LineSeries& s : p.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
    }
  if (!(xhi >= xlo)) throw AnalysisError("line plot: no data to draw");
  if (p.x_log && !(xlo > 0)) throw AnalysisError("line plot: a log x axis needs every x > 0");
  if (p.x_log && p.mark) throw AnalysisError("line plot: a mark on a log x axis is not drawn");
  if (p.y_range) ylo = p.y_range->first, yhi = p.y_range->second;
  RenderReport rep;
  std::size_t named = 0, longest = 0;
  for (const LineSeries& s : p.series)
    if (!s.name.empty()) ++named, longest = std::max(longest, s.name.size());
  rep.legend_outside = named > 1;
  Graph gr(size.width, size.height);
  // A log axis: padded by a factor, and the frame (for label placement) in
  // log10 units, as drawn.
  const auto to_frame = [&](double x) { return p.x_log ? std::log10(x) : x; };
  auto [x0, x1] = p.x_log ? padded(std::log10(xlo), std::log10(xhi)) : padded(xlo, xhi);
  if (p.x_log && xhi > xlo) x0 -= 0.02 * (x1 - x0), x1 += 0.02 * (x1 - x0);
  const auto [y0, y1] = padded(ylo, yhi);
  const LegendLayout lay = legend_layout(named, longest);
  double scale = 1.0;  // the font relative to the plot: larger in a narrower plot
  if (rep.legend_outside) {
    title_and_cell(gr, p.title, lay.plot_width);
    scale = plot_font_scale(lay.plot_width);
  }
  if (p.x_log) {
    gr.SetRanges(std::pow(10.0, x0), std::pow(10.0, x1), y0, y1);
    gr.SetFunc("lg(x)", "");
  } else {
    gr.SetRanges(x0, x1, y0, y1);
  }
  frame(gr, rep.legend_outside ? "" : p.title, p.xlabel, p.ylabel);
  gr.Grid("xy", "h");
  const Frame f{x0, x1, y0, y1};
  std::vector<std::vector<std::pair<double, double>>> lines;
  std::vector<LegendEntry> legend;
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const LineSeries& s = p.series[k];
    if (s.x.empty()) continue;
    Data x(long(s.x.size())), y(long(s.y.size()));
    lines.emplace_back();
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      x.a[i] = s.x[i], y.a[i] = s.y[i];
      lines.back().emplace_back(f.fx(to_frame(s.x[i])), f.fy(s.y[i]));
    }
    const std::string pen =
        s.colour >= 0 ? line_pen(std::size_t(s.colour), std::size_t(std::max(0, s.dash))) : series_pen(k);
    gr.Plot(x, y, pen.c_str());
    rep.pens.push_back(pen);
    if (!s.name.empty()) legend.push_back({s.name, pen});
  }
  if (p.mark) {
    LabelSide side = p.mark->side;
    if (side == LabelSide::automatic)
      side = choose_label_side(f.fx(to_frame(p.mark->x)), f.fy(p.mark->y), p.mark->label.size(), scale, lines);
    put_mark(gr, *p.mark, side, f, scale, false, rep);
  }
  if (rep.legend_outside) {
    if (p.x_log) {  // the legend is placed in frame units: the linear axis of the log values
      gr.SetFunc("", "");
      gr.SetRanges(x0, x1, y0, y1);
    }
    outside_legend(gr, f, legend, lay, 0);
  }
  save(gr, path);
  return rep;
}

void render(const MapPlot& p, const std::string& path, ImageSize size) {
  if (!(p.lx > 0 && p.ly > 0)) throw AnalysisError("map plot: empty map");
  Graph gr(size.width, size.height);
  // The title over the whole width, the map left, its legend right of it
  // (inside, it covered the path).
  std::vector<LegendEntry> legend{{"path", "b"}};
  if (!p.transit_paths.empty()) legend.push_back({"transit", "r2"});
  if (!p.zone_midpoints.empty()) legend.push_back({"zone midpoint", "m+", true});
  if (!p.subgoals.empty()) legend.push_back({"sub-goal", "k.", true});
  if (!p.regions.empty()) legend.push_back({"coverage rectangle", "G3"});
  if (!p.transitions.empty()) legend.push_back({"transition rectangle", "m;2"});
  legend.push_back({"start", "g#o", true});
  legend.push_back({"end", "r#s", true});
  std::size_t longest = 0;
  for (const LegendEntry& e : legend) longest = std::max(longest, e.name.size());
  const LegendLayout lay = legend_layout(legend.size(), longest);
  title_and_cell(gr, p.title, lay.plot_width);
  gr.SetRanges(0, p.lx, 0, p.ly, -1, 1);
  gr.Aspect(p.lx, p.ly);
  frame(gr, "", "x (m)", "y (m)");
  // Covered cells, light; obstacles, dark; then the path on top.
  for (int j = 0; j < p.ny; ++j)
    for (int i = 0; i < p.nx; ++i)
      if (p.covered[std::size_t(j) * std::size_t(p.nx) + std::size_t(i)]) {
        const double x0 = i * p.cell, y0 = j * p.cell;
        gr.FaceZ(mglPoint(x0, y0, -0.5), std::min(p.cell, p.lx - x0), std::min(p.cell, p.ly - y0), "{xDDEEFF}");
      }
  for (const Box2& b : p.obstacles) gr.FaceZ(mglPoint(b.x0, b.y0, -0.4), b.x1 - b.x0, b.y1 - b.y0, "H");
  // Lines and marks above the faces (z = 0.5): MathGL hides what lies below.
  auto draw = [&](const std::vector<std::pair<double, double>>& pts, const char* pen) {
    if (pts.size() < 2) return;
    Data x(long(pts.size())), y(long(pts.size())), z(long(pts.size()));
    for (std::size_t i = 0; i < pts.size(); ++i) x.a[i] = pts[i].first, y.a[i] = pts[i].second, z.a[i] = 0.5;
    gr.Plot(x, y, z, pen);
  };
  for (const auto& path_pts : p.arnold_paths) draw(path_pts, "b");
  for (const auto& path_pts : p.transit_paths) draw(path_pts, "r2");
  for (const auto& [x, y] : p.zone_midpoints) gr.Mark(mglPoint(x, y, 0.6), "m+");
  for (const auto& [x, y] : p.subgoals) gr.Mark(mglPoint(x, y, 0.6), "k.");
  auto outline = [&](const Box2& b, const char* pen) {
    const mglPoint a(b.x0, b.y0, 0.55), c(b.x1, b.y0, 0.55), d(b.x1, b.y1, 0.55), e(b.x0, b.y1, 0.55);
    gr.Line(a, c, pen), gr.Line(c, d, pen), gr.Line(d, e, pen), gr.Line(e, a, pen);
  };
  for (const Box2& b : p.regions) outline(b, "G3");
  for (const Box2& b : p.transitions) outline(b, "m;2");
  gr.Mark(mglPoint(p.start.first, p.start.second, 0.7), "g#o");
  gr.Mark(mglPoint(p.end.first, p.end.second, 0.7), "r#s");
  outside_legend(gr, Frame{0, p.lx, 0, p.ly}, legend, lay, 0.7);
  save(gr, path);
}

}  // namespace chaosweep
