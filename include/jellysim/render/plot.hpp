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

enum class LegendCorner { TopRight, TopLeft, BottomRight, BottomLeft };

struct ChartSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;  ///< log axes (non-positive values are dropped)
  std::vector<Series> series;
  LegendCorner legend = LegendCorner::TopRight;
  int width_px = 960, height_px = 680;
};

/// Writes a line/scatter chart with axes, labels and a legend to a PNG file.
void write_chart_png(const ChartSpec& chart, const std::filesystem::path& png_path);

/// One panel of a strip of 2D drawings (e.g. frames of an animation).
struct Drawing {
  std::string caption;
  std::vector<std::array<Vec2, 2>> segments;  ///< e.g. springs
  std::vector<Vec2> points;                   ///< e.g. point masses
  std::vector<Vec2> marked_points;            ///< e.g. pinned points, drawn larger
};

/// Draws panels side by side (`columns` per row) with a common, equal-aspect view box that contains
/// every panel's content, and writes a PNG file.
void write_drawing_strip_png(const std::vector<Drawing>& panels, int columns, const std::string& title,
                             const std::filesystem::path& png_path, int panel_px = 320);

}  // namespace jellysim::render
