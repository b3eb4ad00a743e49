#pragma once
// The fluid as a colour image for the viewer's 2D panel: one pixel per cell, speed on a sequential
// colour map or vorticity on a diverging one. CPU only (the viewer uploads it as a texture).
#include <array>
#include <cstdint>
#include <vector>

#include "jellysim/fluid/grid.hpp"
#include "jellysim/fluid3d/grid_3d.hpp"

namespace jellysim::viewer {

enum class FieldShown { speed, vorticity };

/// RGBA8, `width` × `height` pixels, row 0 at the bottom of the tank (OpenGL texture order).
struct FieldImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  double max_value = 0.0;  ///< largest |value| of the field (speed m/s or vorticity 1/s)
  double range = 0.0;      ///< the colour range used: speed 0…range, vorticity −range…range
};

/// The colour map (RGB8) at s: speed s ∈ [0, 1] (deep water blue → teal → yellow → white),
/// vorticity s ∈ [−1, 1] (blue, clockwise → dark water → red, counter-clockwise).
std::array<std::uint8_t, 3> field_colour(FieldShown shown, double s);

/// The tracers' colour in the 2D panel, and the muscle springs': a green and a magenta, far from
/// every colour of both maps (test FieldImage.OverlayColoursStandApartFromBothMaps).
inline constexpr std::array<std::uint8_t, 3> kTracerColour{40, 255, 60};
inline constexpr std::array<std::uint8_t, 3> kMuscleColour{240, 90, 240};

/// Colours the flow. `range` > 0 fixes the colour range (speed 0…range, vorticity −range…range);
/// ≤ 0 takes the field's own maximum.
FieldImage field_image(const fluid::FlowState& flow, FieldShown shown, double range);

/// The 3D flow on one x–y plane of cells (k: its index along z), coloured as above: the speed of
/// the in-plane velocity (u, v) or the vorticity's z component ∂v/∂x − ∂u/∂y. `mirror_x`: the
/// grid is the half of the tank x ≥ 0 (a mirror plane at its low x side, the quarter tank): the
/// image shows the whole width, the left half the mirror image (u and ω_z change sign there).
FieldImage field_image(const fluid3d::FlowState3d& flow, int k, FieldShown shown, double range, bool mirror_x);

}  // namespace jellysim::viewer
