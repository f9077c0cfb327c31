#include "analysis/plot.hpp"

#include <mgl2/mgl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "analysis/result_set.hpp"

namespace chaosweep {

namespace fs = std::filesystem;

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
void save(mglGraph& gr, const std::string& path) {
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
    gr.WritePNG(written.c_str(), "", false);
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

void frame(mglGraph& gr, const std::string& title, const std::string& xlabel, const std::string& ylabel) {
  gr.SetFontSize(3.2);
  if (!title.empty()) gr.Title(literal(title).c_str(), "", title.size() > 40 ? -1.1 : -1.4);
  gr.Box();
  gr.Axis("xy");
  gr.Label('x', literal(xlabel).c_str(), 0);
  gr.Label('y', literal(ylabel).c_str(), 0);
}

void put_mark(mglGraph& gr, const PlotMark& m) {
  gr.Mark(mglPoint(m.x, m.y), "k*");
  gr.Mark(mglPoint(m.x, m.y), "wo");
  if (!m.label.empty()) gr.Puts(mglPoint(m.x, m.y), mglPoint(m.x + 1, m.y), literal(" " + m.label).c_str(), ":L", -0.8);
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

void render(const HeatmapPlot& p, const std::string& path, ImageSize size) {
  const long nx = long(p.xs.size()), ny = long(p.ys.size());
  if (nx < 1 || ny < 1 || p.z.size() != std::size_t(nx * ny)) throw AnalysisError("heatmap: no data to draw");
  mglGraph gr(0, size.width, size.height);
  // Cells centred on the axis values: draw on a grid one wider than the data.
  mglData z(nx, ny), x(nx), y(ny);
  double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const double v = p.z[std::size_t(j * nx + i)];
      z.a[i + nx * j] = std::isnan(v) ? mglNaN : v;
      if (!std::isnan(v)) zlo = std::min(zlo, v), zhi = std::max(zhi, v);
    }
  for (long i = 0; i < nx; ++i) x.a[i] = p.xs[std::size_t(i)];
  for (long j = 0; j < ny; ++j) y.a[j] = p.ys[std::size_t(j)];
  if (!(zhi >= zlo)) zlo = 0, zhi = 1;  // every cell empty
  const auto [x0, x1] = padded(p.xs.front(), p.xs.back());
  const auto [y0, y1] = padded(p.ys.front(), p.ys.back());
  const auto [c0, c1] = padded(zlo, zhi);
  gr.SetRanges(x0, x1, y0, y1);
  gr.SetRange('c', c0, c1);
  frame(gr, p.title, p.xlabel, p.ylabel);
  gr.Dens(x, y, z, "BbcyrR");
  gr.Colorbar("BbcyrR>");
  gr.Puts(mglPoint(x1 + (x1 - x0) * 0.16, y1 + (y1 - y0) * 0.06), literal(p.zlabel).c_str(), ":C", -0.9);
  if (p.mark) put_mark(gr, *p.mark);
  save(gr, path);
}

void render(const LinePlot& p, const std::string& path, ImageSize size) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const LineSeries& s : p.series)
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      xlo = std::min(xlo, s.x[i]), xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
    }
  if (!(xhi >= xlo)) throw AnalysisError("line plot: no data to draw");
  if (p.y_range) ylo = p.y_range->first, yhi = p.y_range->second;
  mglGraph gr(0, size.width, size.height);
  const auto [x0, x1] = padded(xlo, xhi);
  const auto [y0, y1] = padded(ylo, yhi);
  gr.SetRanges(x0, x1, y0, y1);
  frame(gr, p.title, p.xlabel, p.ylabel);
  gr.Grid("xy", "h");
  static const char* pens[] = {"b2", "r2", "g2", "m2", "c2", "k2", "q2", "u2"};
  for (std::size_t k = 0; k < p.series.size(); ++k) {
    const LineSeries& s = p.series[k];
    if (s.x.empty()) continue;
    mglData x(long(s.x.size())), y(long(s.y.size()));
    for (std::size_t i = 0; i < s.x.size(); ++i) x.a[i] = s.x[i], y.a[i] = s.y[i];
    const char* pen = pens[k % 8];
    gr.Plot(x, y, pen);
    if (!s.name.empty()) gr.AddLegend(literal(s.name).c_str(), pen);
  }
  if (p.series.size() > 1) gr.Legend(0, "#", "");
  if (p.mark) put_mark(gr, *p.mark);
  save(gr, path);
}

void render(const MapPlot& p, const std::string& path, ImageSize size) {
  if (!(p.lx > 0 && p.ly > 0)) throw AnalysisError("map plot: empty map");
  mglGraph gr(0, size.width, size.height);
  gr.SetRanges(0, p.lx, 0, p.ly, -1, 1);
  gr.Aspect(p.lx, p.ly);
  frame(gr, p.title, "x (m)", "y (m)");
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
    mglData x(long(pts.size())), y(long(pts.size())), z(long(pts.size()));
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
  gr.AddLegend("path", "b");
  if (!p.transit_paths.empty()) gr.AddLegend("transit", "r2");
  if (!p.zone_midpoints.empty()) gr.AddLegend("zone midpoint", "m+");
  if (!p.subgoals.empty()) gr.AddLegend("sub-goal", "k.");
  if (!p.regions.empty()) gr.AddLegend("coverage rectangle", "G3");
  if (!p.transitions.empty()) gr.AddLegend("transition rectangle", "m;2");
  gr.AddLegend("start", "g#o");
  gr.AddLegend("end", "r#s");
  gr.Legend(1, "#", "size -0.75");
  save(gr, path);
}

}  // namespace chaosweep
