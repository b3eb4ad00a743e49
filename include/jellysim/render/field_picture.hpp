#pragma once
// PNG pictures of grid-fluid fields for a person to look at: speed or vorticity as a colour image
// with velocity arrows and tracer particles on top; one picture by our own rasteriser, several
// panels side by side with PLplot (pngcairo device). Output code only.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "jellysim/fluid/grid.hpp"
#include "jellysim/render/image.hpp"

namespace jellysim::render {

enum class FieldQuantity {
  speed,      ///< |u| in m/s, sequential colour map from 0 to the maximum
  vorticity,  ///< ω in 1/s, diverging colour map symmetric about 0
};

struct FieldPicture {
  const fluid::FlowState* state = nullptr;
  std::string caption;
  std::vector<Vec2> tracers_m;  ///< drawn as dots
  std::vector<std::array<Vec2, 2>> segments_m;        ///< e.g. springs of an immersed body, drawn as lines
  std::vector<std::array<Vec2, 2>> thin_segments_m;   ///< e.g. muscle springs, drawn thinner in another colour
  std::optional<std::array<Vec2, 2>> view_m;          ///< lower-left and upper-right corner to show (zoom)
};

struct FieldPictureOptions {
  FieldQuantity quantity = FieldQuantity::speed;
  bool arrows = true;
  int arrows_per_side = 20;  ///< arrow lattice density along the longer side
  /// Colour range: speed 0…max, vorticity −max…max. ≤ 0: taken from the data of each panel.
  double colour_range_max = 0.0;
  int panel_px = 480;
};

/// One picture of one flow, drawn by our own rasteriser (render/image.hpp): the per-frame pictures
/// of a run, where PLplot's per-picture font set-up (pango, fontconfig) took most of the time.
RgbImage draw_field_picture(const FieldPicture& picture, const FieldPictureOptions& options);
/// draw_field_picture as the bytes of a PNG file.
std::string field_png(const FieldPicture& picture, const FieldPictureOptions& options);
/// Several flows side by side, `columns` per row (e.g. thesis Figure 8.7), as the bytes of a PNG
/// file (field_panels_png) or written to one (io::write_file).
std::string field_panels_png(const std::vector<FieldPicture>& panels, int columns, const FieldPictureOptions& options);
void write_field_panels_png(const std::vector<FieldPicture>& panels, int columns,
                            const FieldPictureOptions& options, const std::filesystem::path& png_path);

}  // namespace jellysim::render
