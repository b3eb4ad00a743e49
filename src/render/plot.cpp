#include "jellysim/render/plot.hpp"

#include "jellysim/core/errors.hpp"

#include "plplot_lock.hpp"

#include <plplot/plstream.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace jellysim::render {
namespace {

// A colour-blind-friendly palette (Okabe & Ito), used in order for the series.
constexpr std::array<std::array<int, 3>, 8> kPalette{{{0, 114, 178}, {213, 94, 0}, {0, 158, 115}, {204, 121, 167},
                                                      {230, 159, 0}, {86, 180, 233}, {0, 0, 0}, {240, 228, 66}}};
constexpr int kFirstSeriesColour = 2;  // cmap0 slots 0 (background) and 1 (axes) are reserved

struct Bounds {
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin;
  double ymin = xmin, ymax = -xmin;
  void add(double x, double y) {
    xmin = std::min(xmin, x); xmax = std::max(xmax, x);
    ymin = std::min(ymin, y); ymax = std::max(ymax, y);
  }
  bool empty() const { return !(xmin <= xmax); }
  void pad(double fraction) {
    const double dx = std::max(xmax - xmin, 1e-12), dy = std::max(ymax - ymin, 1e-12);
    xmin -= fraction * dx; xmax += fraction * dx;
    ymin -= fraction * dy; ymax += fraction * dy;
  }
};

/// A round tick spacing (1, 2 or 5 times a power of ten) giving about three ticks over `range`.
double nice_tick(double range) {
  const double raw = range / 2.5;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / power;
  return power * (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0);
}

/// Starts a PNG stream (plplot_png) with a white background and dark axes.
void open_png(plstream& pls, int width, int height) {
  pls.spage(0, 0, width, height, 0, 0);
  pls.scol0(0, 255, 255, 255);
  pls.scol0(1, 30, 30, 30);
  for (std::size_t i = 0; i < kPalette.size(); ++i) {
    pls.scol0(kFirstSeriesColour + static_cast<int>(i), kPalette[i][0], kPalette[i][1], kPalette[i][2]);
  }
  pls.init();
}

/// Values as plotted: log10 on log axes; points with a non-positive log coordinate are dropped.
void plotted_values(const Series& s, bool log_x, bool log_y, std::vector<PLFLT>& x, std::vector<PLFLT>& y) {
  x.clear(); y.clear();
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    double xi = s.x[i], yi = s.y[i];
    if ((log_x && !(xi > 0)) || (log_y && !(yi > 0)) || !std::isfinite(xi) || !std::isfinite(yi)) continue;
    x.push_back(log_x ? std::log10(xi) : xi);
    y.push_back(log_y ? std::log10(yi) : yi);
  }
}

/// Columns and rows of the legend: up to four entries in one column, more in two or three.
std::pair<PLINT, PLINT> legend_grid(std::size_t entries) {
  const PLINT columns = entries <= 4 ? 1 : entries <= 8 ? 2 : 3;
  return {columns, (static_cast<PLINT>(entries) + columns - 1) / columns};
}

void draw_legend(plstream& pls, const ChartSpec& chart) {
  const auto n = static_cast<PLINT>(chart.series.size());
  std::vector<PLINT> opts(n), text_colors(n), line_colors(n), line_styles(n), symbol_colors(n), symbol_numbers(n);
  std::vector<PLFLT> line_widths(n, 2.0), symbol_scales(n, 1.0);
  std::vector<const char*> texts(n), symbols(n);
  for (PLINT i = 0; i < n; ++i) {
    const Series& s = chart.series[static_cast<std::size_t>(i)];
    opts[i] = (s.line ? PL_LEGEND_LINE : 0) | (s.markers ? PL_LEGEND_SYMBOL : 0);
    text_colors[i] = 1;
    line_colors[i] = symbol_colors[i] = kFirstSeriesColour + i % static_cast<PLINT>(kPalette.size());
    line_styles[i] = s.dashed ? 2 : 1;
    symbol_numbers[i] = 1;
    texts[i] = s.label.c_str();
    symbols[i] = "#(728)";
  }
  // Below the plot area and its axis label, in the space kept free there: it hides no data.
  const PLINT position = PL_POSITION_OUTSIDE | PL_POSITION_BOTTOM;  // centred
  PLFLT w = 0, h = 0;
  pls.legend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, position,
             0.0, 0.17, 0.05, 0, 1, 1, legend_grid(chart.series.size()).second, legend_grid(chart.series.size()).first, n, opts.data(), 0.6, 0.7, 1.6, 0.0, text_colors.data(), texts.data(),
             nullptr, nullptr, nullptr, nullptr, line_colors.data(), line_styles.data(), line_widths.data(),
             symbol_colors.data(), symbol_scales.data(), symbol_numbers.data(), symbols.data());
}

/// The largest finite magnitude of the x (or y) values.
double largest_magnitude(const std::vector<Series>& series, bool y_values) {
  double m = 0.0;
  for (const Series& s : series)
    for (double v : y_values ? s.y : s.x)
      if (std::isfinite(v)) m = std::max(m, std::abs(v));
  return m;
}

/// "quantity (unit)", or the quantity alone for a pure number.
std::string axis_label(const std::string& quantity, const std::string& unit) {
  return unit.empty() ? quantity : quantity + " (" + unit + ")";
}

}  // namespace

AxisUnit fitting_unit(const std::string& si_unit, double max_abs) {
  const bool prefixable = !si_unit.empty() && si_unit != "°";
  if (!prefixable || !(max_abs > 0.0) || max_abs >= 0.1) return {si_unit, 1.0};
  const bool length = si_unit == "m" || si_unit.starts_with("m/");
  const std::vector<std::pair<const char*, double>> prefixes =
      length ? std::vector<std::pair<const char*, double>>{{"c", 1e2}, {"m", 1e3}, {"µ", 1e6}}
             : std::vector<std::pair<const char*, double>>{{"m", 1e3}, {"µ", 1e6}};
  for (const auto& [prefix, factor] : prefixes)
    if (max_abs * factor >= 0.1) return {prefix + si_unit, factor};
  return {prefixes.back().first + si_unit, prefixes.back().second};
}

namespace {

/// The chart with its values in the units shown (linear axes only; log axes keep SI units).
ChartSpec in_shown_units(const ChartSpec& chart, std::string& x_label, std::string& y_label) {
  ChartSpec shown = chart;
  const AxisUnit xu = chart.log_x ? AxisUnit{chart.x_unit, 1.0} : fitting_unit(chart.x_unit, largest_magnitude(chart.series, false));
  const AxisUnit yu = chart.log_y ? AxisUnit{chart.y_unit, 1.0} : fitting_unit(chart.y_unit, largest_magnitude(chart.series, true));
  for (Series& s : shown.series) {
    for (double& v : s.x) v *= xu.per_si;
    for (double& v : s.y) v *= yu.per_si;
  }
  x_label = axis_label(chart.x_label, xu.unit);
  y_label = axis_label(chart.y_label, yu.unit);
  return shown;
}

void draw_chart(plstream& pls, const ChartSpec& chart, const Bounds& b, const std::string& x_label,
                const std::string& y_label) {
  open_png(pls, chart.width_px, chart.height_px);
  std::vector<PLFLT> x, y;
  pls.col0(1);
  pls.schr(0, 0.9);
  // The plot area leaves room below for the legend (a line per series).
  pls.adv(0);
  const double legend_height = 0.045 * static_cast<double>(legend_grid(chart.series.size()).second) + 0.03;
  pls.vpor(0.09, 0.96, 0.13 + legend_height, 0.91);
  pls.wind(b.xmin, b.xmax, b.ymin, b.ymax);
  const std::string x_options = std::string("bcnstg") + (chart.log_x ? "l" : "");
  const std::string y_options = std::string("bcnstvg") + (chart.log_y ? "l" : "");
  pls.box(x_options.c_str(), 0.0, 0, y_options.c_str(), 0.0, 0);
  pls.lab(x_label.c_str(), y_label.c_str(), chart.title.c_str());
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const Series& s = chart.series[i];
    plotted_values(s, chart.log_x, chart.log_y, x, y);
    pls.col0(kFirstSeriesColour + static_cast<PLINT>(i % kPalette.size()));
    pls.width(2.0);
    pls.lsty(s.dashed ? 2 : 1);
    if (s.line && x.size() > 1) pls.line(static_cast<PLINT>(x.size()), x.data(), y.data());
    if (s.markers) pls.string(static_cast<PLINT>(x.size()), x.data(), y.data(), "#(728)");
  }
  pls.lsty(1);
  pls.width(1.0);
  draw_legend(pls, chart);
}

}  // namespace

std::string chart_png(const ChartSpec& spec) {
  std::string x_label, y_label;
  const ChartSpec chart = in_shown_units(spec, x_label, y_label);
  Bounds b;
  std::vector<PLFLT> x, y;
  for (const Series& s : chart.series) {
    plotted_values(s, chart.log_x, chart.log_y, x, y);
    for (std::size_t i = 0; i < x.size(); ++i) b.add(x[i], y[i]);
  }
  if (b.empty()) throw RunError("chart '" + chart.title + "' has no finite data to plot");
  b.pad(0.05);

  return plplot_png([&](plstream& pls) { draw_chart(pls, chart, b, x_label, y_label); });
}

void write_chart_png(const ChartSpec& chart, const std::filesystem::path& png_path) {
  io::write_file(png_path, chart_png(chart));
}

namespace {

void draw_strip_panel(plstream& pls, const Drawing& d, const Bounds& b, const std::array<double, 4>& viewport) {
  const auto [vx0, vx1, vy0, vy1] = viewport;
  pls.col0(1);
  pls.adv(0);
  pls.vpor(vx0, vx1, vy0, vy1);
  pls.wind(b.xmin, b.xmax, b.ymin, b.ymax);
  pls.box("bcnst", nice_tick(b.xmax - b.xmin), 0, "bcnstv", nice_tick(b.ymax - b.ymin), 0);
  pls.lab("", "", d.caption.c_str());
  pls.col0(kFirstSeriesColour);
  for (const auto& seg : d.segments) {
    PLFLT x[2] = {seg[0].x, seg[1].x}, y[2] = {seg[0].y, seg[1].y};
    pls.line(2, x, y);
  }
  pls.col0(kFirstSeriesColour + 1);
  pls.ssym(0, 0.6);
  for (Vec2 p : d.points) {
    PLFLT x = p.x, y = p.y;
    pls.string(1, &x, &y, "#(728)");
  }
  pls.col0(1);
  pls.ssym(0, 2.0);
  for (Vec2 p : d.marked_points) {
    PLFLT x = p.x, y = p.y;
    pls.string(1, &x, &y, "#(727)");
  }
  pls.ssym(0, 1.0);
}

}  // namespace

std::string drawing_strip_png(const std::vector<Drawing>& panels, int columns, const std::string& title,
                              int panel_px) {
  if (panels.empty() || columns < 1) throw RunError("drawing strip '" + title + "' has no panels");
  Bounds b;
  for (const Drawing& d : panels) {
    for (const auto& seg : d.segments) { b.add(seg[0].x, seg[0].y); b.add(seg[1].x, seg[1].y); }
    for (Vec2 p : d.points) b.add(p.x, p.y);
    for (Vec2 p : d.marked_points) b.add(p.x, p.y);
  }
  b.pad(0.06);
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  // Panel height follows the content's aspect ratio (plus room for caption and tick labels).
  const double aspect = std::clamp((b.ymax - b.ymin) / (b.xmax - b.xmin), 0.2, 5.0);
  // The viewport fractions below; the panel height makes both axes use the same scale.
  constexpr double vx0 = 0.16, vx1 = 0.97, vy0 = 0.14, vy1 = 0.84;
  const int panel_height_px = static_cast<int>(panel_px * (vx1 - vx0) * aspect / (vy1 - vy0));

  return plplot_png([&](plstream& pls) {
    pls.ssub(columns, rows);
    open_png(pls, columns * panel_px, rows * panel_height_px);
    pls.schr(0, 0.7);
    for (const Drawing& d : panels) draw_strip_panel(pls, d, b, {vx0, vx1, vy0, vy1});
  });
}

}  // namespace jellysim::render
