#include "jellysim/render/field_picture.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "jellysim/fluid/diagnostics.hpp"

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

void draw_arrows(plstream& pls, const fluid::FlowState& s, int per_side) {
  const fluid::MacGrid& g = s.grid;
  const double spacing = std::max(g.width_m, g.height_m) / std::max(per_side, 1);
  const int nx = std::max(1, static_cast<int>(std::round(g.width_m / spacing)));
  const int ny = std::max(1, static_cast<int>(std::round(g.height_m / spacing)));
  double v_max = 0.0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 p = g.world_from_grid((i + 0.5) * g.nx / nx, (j + 0.5) * g.ny / ny);
      v_max = std::max(v_max, norm(s.velocity.sample(p)));
    }
  if (v_max <= 0.0) return;
  const double scale = 0.9 * spacing / v_max;  // the fastest arrow spans 90 % of the spacing
  pls.col0(1);
  pls.width(1.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Vec2 p = g.world_from_grid((i + 0.5) * g.nx / nx, (j + 0.5) * g.ny / ny);
      const Vec2 d = scale * s.velocity.sample(p);
      const Vec2 tip = p + d;
      pls.join(p.x, p.y, tip.x, tip.y);
      const double len = norm(d);
      if (len < 1e-12) continue;
      const Vec2 back = -0.3 * d;
      const Vec2 side = 0.15 * perp(d);
      const Vec2 a = tip + back + side, b = tip + back - side;
      pls.join(tip.x, tip.y, a.x, a.y);
      pls.join(tip.x, tip.y, b.x, b.y);
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

void draw_panel(plstream& pls, const FieldPicture& panel, const FieldPictureOptions& options) {
  if (!panel.state) throw std::invalid_argument("field picture without a flow state");
  const fluid::FlowState& s = *panel.state;
  const fluid::MacGrid& g = s.grid;
  const fluid::Field f = quantity_field(s, options.quantity);
  double range_max = options.colour_range_max;
  if (range_max <= 0.0) range_max = std::max(f.max_abs_interior(), 1e-12);
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

void write_field_panels_png(const std::vector<FieldPicture>& panels, int columns, const FieldPictureOptions& options,
                            const std::filesystem::path& png_path) {
  if (panels.empty()) throw std::invalid_argument("no panels to draw");
  columns = std::clamp(columns, 1, static_cast<int>(panels.size()));
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  plstream pls;
  pls.sdev("pngcairo");
  pls.sfnam(png_path.string().c_str());
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
}

void write_field_png(const FieldPicture& picture, const FieldPictureOptions& options,
                     const std::filesystem::path& png_path) {
  write_field_panels_png({picture}, 1, options, png_path);
}

}  // namespace jellysim::render
