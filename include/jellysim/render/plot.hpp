#pragma once
// Charts and line drawings as PNG files (PLplot with its cairo PNG device). Pure output code:
// it receives numbers and writes pictures, nothing here knows about the physics.
#include "jellysim/math/vec2.hpp"

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace jellysim::render {

struct Series {
  std::string label;
  std::vector<double> x, y;
  bool markers = false;   ///< draw a symbol at each point
  bool line = true;       ///< join the points
  bool dashed = false;
};

/// A chart of series; the legend sits outside the data, below the plot area.
struct ChartSpec {
  std::string title;
  std::string x_label, y_label;  ///< the quantities ("t", "position")
  /// SI units of the values ("s", "m", "m/s"). A linear axis shows them in the prefixed unit that
  /// fits its data (cm, mm/s: fitting_unit), labelled "quantity (unit)"; empty: a pure number.
  std::string x_unit, y_unit;
  bool log_x = false, log_y = false;  ///< log axes (non-positive values are dropped)
  std::vector<Series> series;
  int width_px = 960, height_px = 680;
};

/// A unit to show values of SI `unit` whose largest magnitude is max_abs: the unit itself, or its
/// centi- (lengths only), milli- or micro- form, the first that makes max_abs at least 0.1
/// (degrees and pure numbers keep theirs).
struct AxisUnit {
  std::string unit;
  double per_si = 1.0;  ///< shown value = SI value × per_si
};
AxisUnit fitting_unit(const std::string& si_unit, double max_abs);

/// A line/scatter chart with axes, labels and a legend, as the bytes of a PNG file.
std::string chart_png(const ChartSpec& chart);
/// Writes chart_png to a file (io::write_file).
void write_chart_png(const ChartSpec& chart, const std::filesystem::path& png_path);

/// One panel of a strip of 2D drawings (e.g. frames of an animation).
struct Drawing {
  std::string caption;
  std::vector<std::array<Vec2, 2>> segments;  ///< e.g. springs
  std::vector<Vec2> points;                   ///< e.g. point masses
  std::vector<Vec2> marked_points;            ///< e.g. pinned points, drawn larger
};

/// Draws panels side by side (`columns` per row) with a common, equal-aspect view box that contains
/// every panel's content: the bytes of a PNG file.
std::string drawing_strip_png(const std::vector<Drawing>& panels, int columns, const std::string& title,
                              int panel_px = 320);

}  // namespace jellysim::render
