#include "jellysim/render/field_picture.hpp"

#include "plplot_lock.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "jellysim/fluid/diagnostics.hpp"
#include "jellysim/render/image.hpp"

namespace jellysim::render {
namespace {

// Colour map 1: sequential (dark blue → teal → yellow) for speed, diverging (blue → white → red)
// for vorticity.
void set_colour_map(plstream& pls, FieldQuantity q) {
  if (q == FieldQuantity::speed) {
    PLFLT pos[] = {0.0, 0.35, 0.7, 1.0};
    PLFLT r[] = {0.07, 0.13, 0.45, 0.99};
    PLFLT g[] = {0.04, 0.45, 0.78, 0.91};
    PLFLT b[] = {0.30, 0.56, 0.37, 0.15};
    pls.scmap1l(true, 4, pos, r, g, b, nullptr);
  } else {
    PLFLT pos[] = {0.0, 0.5, 1.0};
    PLFLT r[] = {0.15, 1.0, 0.75};
    PLFLT g[] = {0.30, 1.0, 0.10};
    PLFLT b[] = {0.75, 1.0, 0.12};
    pls.scmap1l(true, 3, pos, r, g, b, nullptr);
  }
}

fluid::Field quantity_field(const fluid::FlowState& s, FieldQuantity q) {
  return q == FieldQuantity::speed ? fluid::speed_at_centres(s.velocity) : fluid::vorticity_at_centres(s.velocity);
}

void draw_image(plstream& pls, const fluid::Field& f, FieldQuantity q, double range_max) {
  const fluid::MacGrid& g = f.grid();
  const double lo = q == FieldQuantity::speed ? 0.0 : -range_max;
  // Values are clamped into the colour range so that nothing outside it is left blank.
  std::vector<std::vector<PLFLT>> columns(static_cast<std::size_t>(g.nx), std::vector<PLFLT>(g.ny));
  std::vector<const PLFLT*> rows(static_cast<std::size_t>(g.nx));
  for (int i = 0; i < g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) columns[i][j] = std::clamp(f(i, j), lo, range_max);
    rows[i] = columns[i].data();
  }
  const double x0 = g.origin_m.x, x1 = x0 + g.width_m, y0 = g.origin_m.y, y1 = y0 + g.height_m;
  pls.imagefr(rows.data(), g.nx, g.ny, x0, x1, y0, y1, lo, range_max, lo, range_max, nullptr, nullptr);
}

/// The velocity arrows: points on a lattice of about `per_side` along the longer side, each with
/// its velocity scaled so that the fastest arrow spans 90 % of the spacing (none at rest).
std::vector<std::array<Vec2, 2>> arrow_lattice(const fluid::FlowState& s, int per_side) {
  const fluid::MacGrid& g = s.grid;
  const double spacing = std::max(g.width_m, g.height_m) / std::max(per_side, 1);
  const int nx = std::max(1, static_cast<int>(std::round(g.width_m / spacing)));
  const int ny = std::max(1, static_cast<int>(std::round(g.height_m / spacing)));
  std::vector<std::array<Vec2, 2>> arrows;
  double v_max = 0.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 p = g.world_from_grid((i + 0.5) * g.nx / nx, (j + 0.5) * g.ny / ny);
      const Vec2 v = s.velocity.sample(p);
      v_max = std::max(v_max, norm(v));
      arrows.push_back({p, v});
    }
  if (v_max <= 0.0) return {};
  for (auto& a : arrows) a[1] = (0.9 * spacing / v_max) * a[1];
  return arrows;
}

/// An arrow from p along d as three segments: the shaft and two barbs.
std::array<std::array<Vec2, 2>, 3> arrow_segments(Vec2 p, Vec2 d) {
  const Vec2 tip = p + d, back = -0.3 * d, side = 0.15 * perp(d);
  return {{{p, tip}, {tip, tip + back + side}, {tip, tip + back - side}}};
}

void draw_arrows(plstream& pls, const fluid::FlowState& s, int per_side) {
  pls.col0(1);
  pls.width(1.0);
  for (const auto& [p, d] : arrow_lattice(s, per_side)) {
    if (norm(d) < 1e-12) continue;
    for (const auto& seg : arrow_segments(p, d)) pls.join(seg[0].x, seg[0].y, seg[1].x, seg[1].y);
  }
}

void draw_tracers(plstream& pls, const std::vector<Vec2>& tracers) {
  if (tracers.empty()) return;
  std::vector<PLFLT> x, y;
  for (const Vec2& p : tracers) {
    x.push_back(p.x);
    y.push_back(p.y);
  }
  pls.col0(2);
  pls.ssym(0, 0.4);
  pls.poin(static_cast<PLINT>(x.size()), x.data(), y.data(), 17);
  pls.ssym(0, 1.0);
}

void draw_segments(plstream& pls, const std::vector<std::array<Vec2, 2>>& segments, int colour, double width) {
  if (segments.empty()) return;
  pls.col0(colour);
  pls.width(width);
  for (const auto& s : segments) pls.join(s[0].x, s[0].y, s[1].x, s[1].y);
  pls.width(1.0);
}

std::string range_caption(FieldQuantity q, double range_max) {
  char text[96];
  if (q == FieldQuantity::speed) std::snprintf(text, sizeof text, "speed 0 - %.3g m/s", range_max);
  else std::snprintf(text, sizeof text, "vorticity +-%.3g 1/s", range_max);
  return text;
}

/// The colour range's upper end: the option's, or the field's largest magnitude.
double colour_range(const fluid::Field& f, const FieldPictureOptions& options) {
  return options.colour_range_max > 0.0 ? options.colour_range_max : std::max(f.max_abs_interior(), 1e-12);
}

const fluid::FlowState& state_of(const FieldPicture& panel) {
  if (!panel.state) throw std::invalid_argument("field picture without a flow state");
  return *panel.state;
}

void draw_panel(plstream& pls, const FieldPicture& panel, const FieldPictureOptions& options) {
  const fluid::FlowState& s = state_of(panel);
  const fluid::MacGrid& g = s.grid;
  const fluid::Field f = quantity_field(s, options.quantity);
  const double range_max = colour_range(f, options);
  pls.col0(1);
  if (panel.view_m) {
    const auto& v = *panel.view_m;
    pls.env(v[0].x, v[1].x, v[0].y, v[1].y, 1, 0);
  } else {
    pls.env(g.origin_m.x, g.origin_m.x + g.width_m, g.origin_m.y, g.origin_m.y + g.height_m, 1, 0);
  }
  draw_image(pls, f, options.quantity, range_max);
  if (options.arrows) draw_arrows(pls, s, options.arrows_per_side);
  draw_tracers(pls, panel.tracers_m);
  draw_segments(pls, panel.thin_segments_m, 3, 1.0);
  draw_segments(pls, panel.segments_m, 1, 2.5);
  pls.col0(1);
  pls.box("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  pls.lab("x (m)", "y (m)", (panel.caption + "  [" + range_caption(options.quantity, range_max) + "]").c_str());
}

}  // namespace

std::string field_panels_png(const std::vector<FieldPicture>& panels, int columns, const FieldPictureOptions& options) {
  if (panels.empty()) throw std::invalid_argument("no panels to draw");
  columns = std::clamp(columns, 1, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  return plplot_png([&](plstream& pls) {
    pls.spage(0, 0, columns * options.panel_px, rows * options.panel_px, 0, 0);
    pls.scol0(0, 255, 255, 255);  // background
    pls.scol0(1, 20, 20, 20);     // axes, arrows
    pls.scol0(2, 230, 30, 160);   // tracers
    pls.scol0(3, 30, 110, 240);   // thin segments (muscles)
    pls.ssub(columns, rows);
    pls.init();
    set_colour_map(pls, options.quantity);
    pls.schr(0, 0.7);
    for (const FieldPicture& p : panels) draw_panel(pls, p, options);
  });
}

void write_field_panels_png(const std::vector<FieldPicture>& panels, int columns, const FieldPictureOptions& options,
                            const std::filesystem::path& png_path) {
  io::write_file(png_path, field_panels_png(panels, columns, options));
}

namespace {

/// The colour maps of set_colour_map, for our own rasteriser: t in [0, 1].
Rgb colour_at(FieldQuantity q, double t) {
  static const std::vector<std::array<double, 4>> speed{
      {0.0, 0.07, 0.04, 0.30}, {0.35, 0.13, 0.45, 0.56}, {0.7, 0.45, 0.78, 0.37}, {1.0, 0.99, 0.91, 0.15}};
  static const std::vector<std::array<double, 4>> vorticity{
      {0.0, 0.15, 0.30, 0.75}, {0.5, 1.0, 1.0, 1.0}, {1.0, 0.75, 0.10, 0.12}};
  const auto& map = q == FieldQuantity::speed ? speed : vorticity;
  t = std::clamp(t, 0.0, 1.0);
  std::size_t k = 1;
  while (k + 1 < map.size() && t > map[k][0]) ++k;
  const double f = (t - map[k - 1][0]) / (map[k][0] - map[k - 1][0]);
  Rgb c;
  for (std::size_t i = 0; i < 3; ++i)
    c[i] = static_cast<std::uint8_t>(std::lround(255.0 * (map[k - 1][i + 1] + f * (map[k][i + 1] - map[k - 1][i + 1]))));
  return c;
}

/// Tick positions at 1, 2 or 5 times a power of ten, about five across [lo, hi].
std::vector<double> ticks(double lo, double hi) {
  const double raw = (hi - lo) / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double step = raw / p < 1.5 ? p : raw / p < 3.5 ? 2 * p : raw / p < 7.5 ? 5 * p : 10 * p;
  std::vector<double> t;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  return t;
}

std::string tick_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// Where the plot sits in a square panel: the view (m), its scale and the plot area (pixels). The
// plot area keeps the view's aspect ratio, centred in what the margins leave.
struct PlotFrame {
  std::array<Vec2, 2> view;
  double px_per_m = 1.0;
  int text = 1;  // text scale
  int x0 = 0, y0 = 0, plot_w = 0, plot_h = 0;
  Vec2 to_px(Vec2 p) const { return Vec2{(p.x - view[0].x) * px_per_m, (view[1].y - p.y) * px_per_m}; }
};

PlotFrame plot_frame(const std::array<Vec2, 2>& view, int size) {
  PlotFrame pf;
  pf.view = view;
  pf.text = size >= 400 ? 2 : 1;
  const int text = pf.text;
  const int left = 34 * text, bottom = 26 * text, top = 26 * text, right = 8 * text;
  const double view_w = view[1].x - view[0].x, view_h = view[1].y - view[0].y;
  pf.px_per_m = std::min((size - left - right) / view_w, (size - top - bottom) / view_h);
  pf.plot_w = static_cast<int>(view_w * pf.px_per_m);
  pf.plot_h = static_cast<int>(view_h * pf.px_per_m);
  pf.x0 = left + (size - left - right - pf.plot_w) / 2;
  pf.y0 = top + (size - top - bottom - pf.plot_h) / 2;
  return pf;
}

// The field: each pixel takes its cell's value (cell centres are the field's samples), coloured
// over [lo, range_max].
void paint_field(RgbImage& plot, const PlotFrame& pf, const fluid::Field& f, FieldQuantity quantity, double lo,
                 double range_max) {
  const fluid::MacGrid& g = f.grid();
  for (int py = 0; py < pf.plot_h; ++py)
    for (int px = 0; px < pf.plot_w; ++px) {
      const Vec2 w{pf.view[0].x + (px + 0.5) / pf.px_per_m, pf.view[1].y - (py + 0.5) / pf.px_per_m};
      const int i = static_cast<int>(std::floor((w.x - g.origin_m.x) / g.dx()));
      const int j = static_cast<int>(std::floor((w.y - g.origin_m.y) / g.dy()));
      if (i < 0 || j < 0 || i >= g.nx || j >= g.ny) continue;
      plot.set(px, py, colour_at(quantity, (f(i, j) - lo) / (range_max - lo)));
    }
}

// Velocity arrows (optional), tracers, thin segments (scheduled springs) and the body's segments.
void draw_overlays(RgbImage& plot, const PlotFrame& pf, const FieldPicture& panel, const fluid::FlowState& s,
                   const FieldPictureOptions& options, Rgb ink) {
  if (options.arrows)
    for (const auto& [p, d] : arrow_lattice(s, options.arrows_per_side)) {
      if (norm(d) < 1e-12) continue;
      for (const auto& seg : arrow_segments(p, d)) {
        const Vec2 a = pf.to_px(seg[0]), b = pf.to_px(seg[1]);
        draw_segment(plot, a.x, a.y, b.x, b.y, 1.0, ink);
      }
    }
  for (Vec2 p : panel.tracers_m) {
    const Vec2 q = pf.to_px(p);
    draw_disc(plot, q.x, q.y, 1.2, Rgb{230, 30, 160});
  }
  for (const auto& seg : panel.thin_segments_m) {
    const Vec2 a = pf.to_px(seg[0]), b = pf.to_px(seg[1]);
    draw_segment(plot, a.x, a.y, b.x, b.y, 1.0, Rgb{30, 110, 240});
  }
  for (const auto& seg : panel.segments_m) {
    const Vec2 a = pf.to_px(seg[0]), b = pf.to_px(seg[1]);
    draw_segment(plot, a.x, a.y, b.x, b.y, 2.5, ink);
  }
}

// Frame, ticks and axis labels around the plot area.
void draw_axes(RgbImage& image, const PlotFrame& pf, Rgb ink) {
  const int x0 = pf.x0, y0 = pf.y0, plot_w = pf.plot_w, plot_h = pf.plot_h, text = pf.text;
  draw_segment(image, x0, y0, x0 + plot_w, y0, 1.0, ink);
  draw_segment(image, x0, y0 + plot_h, x0 + plot_w, y0 + plot_h, 1.0, ink);
  draw_segment(image, x0, y0, x0, y0 + plot_h, 1.0, ink);
  draw_segment(image, x0 + plot_w, y0, x0 + plot_w, y0 + plot_h, 1.0, ink);
  for (double v : ticks(pf.view[0].x, pf.view[1].x)) {
    const double x = x0 + (v - pf.view[0].x) * pf.px_per_m;
    draw_segment(image, x, y0 + plot_h, x, y0 + plot_h - 4 * text, 1.0, ink);
    draw_text(image, static_cast<int>(x) - 6 * text, y0 + plot_h + 3 * text, tick_text(v), text, ink);
  }
  for (double v : ticks(pf.view[0].y, pf.view[1].y)) {
    const double y = y0 + (pf.view[1].y - v) * pf.px_per_m;
    draw_segment(image, x0, y, x0 + 4 * text, y, 1.0, ink);
    draw_text(image, std::max(0, x0 - static_cast<int>(tick_text(v).size()) * 5 * text - 3 * text),
              static_cast<int>(y) - 3 * text, tick_text(v), text, ink);
  }
  draw_text(image, x0 + plot_w / 2 - 15 * text, y0 + plot_h + 13 * text, "x (m)", text, ink);
  draw_text(image, 2, y0 - 11 * text, "y (m)", text, ink);
}

}  // namespace

RgbImage draw_field_picture(const FieldPicture& panel, const FieldPictureOptions& options) {
  const fluid::FlowState& s = state_of(panel);
  const fluid::MacGrid& g = s.grid;
  const fluid::Field f = quantity_field(s, options.quantity);
  const double range_max = colour_range(f, options);
  const std::array<Vec2, 2> view = panel.view_m ? *panel.view_m
                                                : std::array<Vec2, 2>{g.origin_m, g.origin_m + Vec2{g.width_m, g.height_m}};
  const int size = options.panel_px;
  const PlotFrame pf = plot_frame(view, size);
  const Rgb ink{20, 20, 20};
  RgbImage image(size, size, Rgb{255, 255, 255});
  RgbImage plot(pf.plot_w, pf.plot_h, Rgb{255, 255, 255});
  const double lo = options.quantity == FieldQuantity::speed ? 0.0 : -range_max;
  paint_field(plot, pf, f, options.quantity, lo, range_max);
  draw_overlays(plot, pf, panel, s, options, ink);
  paste(image, plot, pf.x0, pf.y0);
  draw_axes(image, pf, ink);
  draw_text(image, pf.x0, 3 * pf.text, panel.caption + "  [" + range_caption(options.quantity, range_max) + "]",
            pf.text, ink);
  return image;
}

std::string field_png(const FieldPicture& picture, const FieldPictureOptions& options) {
  return png_bytes(draw_field_picture(picture, options));
}

}  // namespace jellysim::render
