#pragma once
// MathGL, loaded when the first figure is drawn (plot.cpp alone uses it).
// Linked into the binary, libmgl reads its 5.6 MB default font and starts
// OpenMP as it loads: ~40 ms added to every command (a sweep, plan, status)
// that draws nothing. The calls are MathGL's C API, made as mgl2/mgl.h's
// inline mglGraph methods make them, so a figure is drawn as before.
#include <mgl2/mgl_cf.h>

#include <cstddef>

namespace chaosweep::mathgl {

// The C functions plot.cpp calls, resolved from the library at first use.
struct Api {
// clang-format off
#define CHAOSWEEP_MGL_FUNCTIONS(X) \
  X(create_graph) X(use_graph) X(delete_graph) X(get_width) X(get_height) X(set_font_size) \
  X(set_cut) X(set_ranges) X(set_range_val) X(set_func) X(title) X(box_str) \
  X(axis) X(axis_grid) X(label) X(mark) X(line) X(facez) \
  X(puts) X(colorbar) X(multiplot_d) X(aspect) X(plot_xy) X(plot_xyz) \
  X(write_png_solid) X(write_svg) X(write_eps) X(write_prc) X(create_data_size) X(data_data) \
  X(delete_data)
// clang-format on
#define CHAOSWEEP_MGL_MEMBER(name) decltype(&::mgl_##name) name = nullptr;
  CHAOSWEEP_MGL_FUNCTIONS(CHAOSWEEP_MGL_MEMBER)
#undef CHAOSWEEP_MGL_MEMBER
};

// The library's functions (dlopen of its soname, once, thread-safe); an
// AnalysisError naming the library and what failed when it cannot be loaded.
const Api& api();

// An mglData of n values (nx = n), freed with it.
class Data {
 public:
  explicit Data(long n) : d_(api().create_data_size(n, 1, 1)), a(api().data_data(d_)) {}
  ~Data() { api().delete_data(d_); }
  Data(const Data&) = delete;
  Data& operator=(const Data&) = delete;
  HCDT get() const { return d_; }

 private:
  HMDT d_;

 public:
  mreal* const a;  // its values, as mglData::a
};

// The mglGraph methods plot.cpp draws with, their defaults and calls as in
// mgl2/mgl.h; the constructor is mglGraph(0, width, height): a bitmap canvas.
class Graph {
 public:
  Graph(int width, int height) : gr_(api().create_graph(width, height)) {}
  ~Graph() {
    if (api().use_graph(gr_, -1) < 1) api().delete_graph(gr_);
  }
  Graph(const Graph&) = delete;
  Graph& operator=(const Graph&) = delete;

  int GetWidth() { return api().get_width(gr_); }
  int GetHeight() { return api().get_height(gr_); }
  void SetFontSize(double size) { api().set_font_size(gr_, size); }
  void SetCut(bool cut) { api().set_cut(gr_, cut); }
  void SetRanges(double x1, double x2, double y1, double y2, double z1 = 0, double z2 = 0) {
    api().set_ranges(gr_, x1, x2, y1, y2, z1, z2);
  }
  void SetRange(char dir, double v1, double v2) { api().set_range_val(gr_, dir, v1, v2); }
  void SetFunc(const char* EqX, const char* EqY, const char* EqZ = nullptr, const char* EqA = nullptr) {
    api().set_func(gr_, EqX, EqY, EqZ, EqA);
  }
  void Title(const char* title, const char* stl = "", double size = -2) { api().title(gr_, title, stl, size); }
  void Box(const char* col = "", bool ticks = true) { api().box_str(gr_, col, ticks); }
  void Axis(const char* dir = "xyzt", const char* stl = "", const char* opt = "") { api().axis(gr_, dir, stl, opt); }
  void Grid(const char* dir = "xyzt", const char* pen = "B", const char* opt = "") {
    api().axis_grid(gr_, dir, pen, opt);
  }
  void Label(char dir, const char* text, double pos = +1, const char* opt = "") {
    api().label(gr_, dir, text, pos, opt);
  }
  void Mark(mglPoint p, const char* mark) { api().mark(gr_, p.x, p.y, p.z, mark); }
  void Line(mglPoint p1, mglPoint p2, const char* pen = "B", int n = 2) {
    api().line(gr_, p1.x, p1.y, p1.z, p2.x, p2.y, p2.z, pen, n);
  }
  void FaceZ(mglPoint p, double wx, double wy, const char* stl = "w", double dx = 0, double dy = 0) {
    api().facez(gr_, p.x, p.y, p.z, wx, wy, stl, dx, dy);
  }
  void Puts(mglPoint p, const char* text, const char* font = ":C", double size = -1) {
    api().puts(gr_, p.x, p.y, p.z, text, font, size);
  }
  void Puts(double x, double y, const char* text, const char* font = ":AC", double size = -1) {
    api().puts(gr_, x, y, 0, text, font, size);
  }
  void Colorbar(const char* sch = "", const char* opt = "") { api().colorbar(gr_, sch, opt); }
  void MultiPlot(int nx, int ny, int m, int dx, int dy, const char* style = "<>_^", double sx = 0, double sy = 0) {
    api().multiplot_d(gr_, nx, ny, m, dx, dy, style, sx, sy);
  }
  void Aspect(double Ax, double Ay, double Az = 1) { api().aspect(gr_, Ax, Ay, Az); }
  void Plot(const Data& x, const Data& y, const char* pen = "", const char* opt = "") {
    api().plot_xy(gr_, x.get(), y.get(), pen, opt);
  }
  void Plot(const Data& x, const Data& y, const Data& z, const char* pen = "", const char* opt = "") {
    api().plot_xyz(gr_, x.get(), y.get(), z.get(), pen, opt);
  }
  // WritePNG with alpha = false (the only one plot.cpp writes).
  void WritePNGSolid(const char* fname, const char* descr = "") { api().write_png_solid(gr_, fname, descr); }
  void WriteSVG(const char* fname, const char* descr = "") { api().write_svg(gr_, fname, descr); }
  void WriteEPS(const char* fname, const char* descr = "") { api().write_eps(gr_, fname, descr); }
  void WritePRC(const char* fname, const char* descr = "", bool make_pdf = true) {
    api().write_prc(gr_, fname, descr, make_pdf);
  }

 private:
  HMGL gr_;
};

}  // namespace chaosweep::mathgl
