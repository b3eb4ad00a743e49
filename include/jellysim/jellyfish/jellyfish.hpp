#pragma once
// The 2D jellyfish slice of thesis §7.1 (Figure 7.2 right, Figure 7.5) as a spring-mass body:
//  * the umbrella: a string of points along the subumbrellar surface, joined by linear springs
//    (mesoglea) and angular springs (bending); or the dense linear-spring mesh of Fig. 7.2 left;
//  * subumbrellar muscle springs across the bell between opposing points, whose rest lengths the
//    contraction function drives (eq. 7.5) with a neural phase delay per spring (§6.2, §7.1);
//  * two tentacle strands hanging from the aperture, with linear and angular springs.
// Units: metres, seconds; spring constants are per metre of slice depth (see docs/jellyfish.md).
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "jellysim/elastic/body.hpp"
#include "jellysim/jellyfish/contraction.hpp"
#include "jellysim/jellyfish/slice_frame.hpp"

namespace jellysim::core {
class StateArchive;
}

namespace jellysim::jellyfish {

enum class UmbrellaModel { angular, mesh };

/// How the slice's springs get their constants (docs/jellyfish.md, "Elastic models"):
///  * continuum (the default): from material quantities that do not mention the marker spacing
///    (ContinuumMaterial), discretised so that a spacing of ds, ds/2 or ds/4 describes the same
///    body: spring constants S / l, joints B / l̄, muscles k_m · (band of bell height) / L, point
///    masses ρ · (arc length);
///  * thesis: per spring as §7.1 builds it (κ_l = λA/l_r with A = ϑ², κ_θ = f κ_l l_r², muscles of
///    cross-section gap², one point mass per marker), which changes the body when the spacing
///    changes (the bending stiffness falls as ds², the muscles' total pull as ds). The chapter 8
///    studies use it on the thesis's tank.
enum class ElasticModel { continuum, thesis };

/// What a tentacle's root joint holds the strand's first segment against (docs/jellyfish.md,
/// "Tentacles that trail"):
///  * axis: the aperture chord (the line between the two margins, across the swimming axis), at the
///    angle the strand has at the start: the tentacle hangs along the swimming axis whatever the
///    margin's tilt, anchored in the margin's ring;
///  * margin: the bell's last segment, as §7.1 builds it: the tentacle continues the margin's
///    tangent, so it swings under the bell whenever the margin turns inward (the recovery stroke);
///  * automatic: axis for the continuum model, margin for the thesis's (its figures bit for bit).
enum class TentacleRoot { automatic, axis, margin };

/// The slice's material per metre of slice depth for the continuum model. The defaults are the
/// thesis construction of the built-in bell (λ = 1.186e6 Pa, ϑ = 1.5 mm, bending factor 10,
/// muscles 4e5 Pa, tentacles 3 ϑ², one bending factor) evaluated at the built-in marker spacing
/// 1.2246 mm (96 × 128 cells), so that at that spacing it is the thesis's bell (docs/jellyfish.md).
struct ContinuumMaterial {
  double stretching_n_per_m = 2.6685;       ///< S: bell tension per unit strain (a plate: E·h)
  double bending_n_m = 4.0e-5;              ///< B: bell bending moment per unit curvature (a plate: E·h³/12)
  double muscle_n_per_m2 = 427.0;           ///< k_m: muscle tension per unit strain, per metre of bell height
  double tentacle_stretching_n_per_m = 8.0055;   ///< S of a tentacle
  double tentacle_bending_n_m = 1.09e-5;         ///< B of a tentacle
  double line_density_kg_per_m2 = 0.8166;        ///< bell mass per metre of arc (fluid-free model only)
  double tentacle_line_density_kg_per_m2 = 2.571;  ///< tentacle mass per metre (fluid-free model only)
};

struct JellyfishSpec {
  // Shape (Fig. 8.21).
  Vec2 aperture_centre_m{0.12, 0.08};   ///< centre of the aperture (bell opening)
  double tilt_rad = 0.0;              ///< rotation of the swimming axis from +y, counter-clockwise
  double diameter_m = 0.04;
  double height_m = 0.028;
  double tentacle_length_m = 0.014;
  double thickness_m = 0.0015;        ///< umbrella thickness ϑ
  double max_spacing_m = 0.0003125;   ///< marker spacing bound (Peskin: ≤ Δx/2 of the built-in tank)
  int min_segments_per_side = 6;
  UmbrellaModel model = UmbrellaModel::angular;
  ElasticModel elastic_model = ElasticModel::continuum;
  ContinuumMaterial material{};           ///< the continuum model's material
  TentacleRoot tentacle_root = TentacleRoot::automatic;  ///< what the tentacles' root joints hold against

  // The thesis model's material (eq. 7.1, κ_l = λ A / l_r; forces per metre of depth).
  double bell_modulus_pa = 1.186e6;       ///< bell mesoglea λ
  double muscle_modulus_pa = 4.0e5;       ///< circumferential muscle λ
  double bending_factor = 10.0;           ///< κ_θ = factor · κ_l l_r² for the umbrella's angular springs
  double tentacle_volume_fraction = 3.0;  ///< tentacle springs' volume relative to the umbrella's (thesis: 0.01)
  double tentacle_bending_factor = 1.0;   ///< κ_θ = factor · κ_l · l_r² for the tentacles' angular springs
  double point_mass_kg = 1e-3;            ///< per marker (thesis model; used only by the fluid-free model)

  // Contraction (§7.1).
  double frequency_hz = 0.7;
  double gamma = 0.56;                    ///< contracted fraction of the rest length (eq. 7.5)
  ContractionProfile profile{};           ///< shape and contraction fraction for every spring
  double aperture_expansion_exponent = 2.0;  ///< expansion exponent p of the aperture-most spring (apex: 1)
  double neural_delay_s = 0.03;           ///< activation delay across the umbrella (Fig. 6.9)
  bool closed_loop = false;               ///< eq. 7.2 controller instead of the open-loop function
  double controller_alpha = 2.0;
  double phase_cycles = 0.0;              ///< phase offset of this individual (for several jellyfish)

  // Steering (beyond the thesis, whose turning attempt failed, §9.2.2): the angular springs of one
  // side of the umbrella are driven like muscles, their rest angles bent further inward in step
  // with the contraction, so that side strokes harder and the jellyfish turns.
  bool steering = false;
  Vec2 steer_target_m{0.12, 0.28};        ///< the point to turn toward
  double steer_gain = 0.3;                ///< extra bend of the side per radian of heading error
  double steer_max_bend_rad = 20.0 * std::numbers::pi / 180.0;  ///< largest extra bend of a side (shared by its joints)
  double steer_damping_cycles = 1.5;      ///< derivative time: heading change per cycle is weighed by this

  int noise_seed = 1;                     ///< the individual's noise seed for rendering (§7.3)

  /// The slice of a body of revolution about its own axis (axisymmetric water, coupling::TankSpec::
  /// geometry): every point is a ring and every force the whole ring's (N, not N per metre of
  /// depth). Meridional springs and joints carry their ring's circumference, the umbrella gets hoop
  /// springs, the muscles become ring (coronal) muscles; see make_rings and docs/jellyfish.md.
  bool rings = false;
};

/// Indices into the body of the parts of the slice.
struct JellyfishLayout {
  std::vector<int> umbrella;               ///< subumbrellar points, left tip → apex → right tip
  std::vector<int> exumbrella;             ///< mesh model only: the outer row, same order
  std::vector<std::vector<int>> tentacles; ///< each from the aperture outward
  std::vector<int> muscle_springs;         ///< indices into body.linear
  std::vector<double> muscle_uncontracted_m;
  std::vector<ContractionProfile> muscle_profiles;
  std::vector<double> muscle_delay_s;
  std::vector<int> hoop_springs;           ///< ring jellyfish only: hoop springs across the axis (make_rings)
  int apex = 0;                            ///< index into umbrella (the middle)
};

class Jellyfish {
 public:
  /// Builds the slice in a body of its own.
  explicit Jellyfish(const JellyfishSpec& spec);
  Jellyfish(const Jellyfish&) = delete;  // body() may point into a world's body
  Jellyfish& operator=(const Jellyfish&) = delete;

  /// Moves the markers and springs into `shared` (a world's body holding several bodies' markers,
  /// which must outlive this jellyfish): from then on the jellyfish reads and actuates them there,
  /// and layout() indexes `shared`. There is one copy of the state; nothing is copied back.
  void move_into(elastic::Body& shared);

  const JellyfishSpec& spec() const { return spec_; }
  /// Indices into body() of the parts of the slice.
  const JellyfishLayout& layout() const { return layout_; }
  /// The body the markers live in: the jellyfish's own, or the shared one it was moved into.
  elastic::Body& body() { return *body_; }
  const elastic::Body& body() const { return *body_; }
  /// The jellyfish's points, linear and angular springs are these index ranges of body().
  std::size_t first_point() const { return first_point_; }
  std::size_t point_count() const { return point_count_; }
  std::size_t first_linear_spring() const { return first_linear_; }
  std::size_t linear_spring_count() const { return base_stiffness_.size(); }
  std::size_t first_angular_spring() const { return first_angular_; }
  std::size_t angular_spring_count() const { return base_joint_stiffness_.size(); }

  /// Sets the muscle rest lengths for time t (eq. 7.5 with each spring's profile and delay, or the
  /// eq. 7.2 controller).
  void actuate(double t);
  /// Q of muscle k at time t (open loop).
  double muscle_activation(std::size_t k, double t) const;

  /// The recorded state for rendering (positions of the body as it is now).
  SliceFrame slice_frame(double t) const;
  /// Umbrella points (subumbrellar surface) as positions.
  std::vector<Vec2> umbrella_points() const;
  /// Unit vector from the aperture centre to the apex at the start (the swimming axis).
  Vec2 initial_axis() const { return rotated(Vec2{0.0, 1.0}, spec_.tilt_rad); }
  /// Unit vector from the aperture centre to the apex now.
  Vec2 heading() const;

  // Live edits (the interactive viewer and steering).
  /// New contraction frequency; the phase offset changes so the phase at time t stays the same.
  void set_frequency(double hz, double t);
  void set_gamma(double gamma);
  /// Scales the umbrella and tentacle spring constants relative to those built from the spec.
  void set_stiffness_scale(double scale);
  void set_steer_target(std::optional<Vec2> target_m);
  /// The steering bias now: signed extra bend (rad) of the steering side at full contraction,
  /// shared by its joints; positive bends the left side (umbrella start) inward.
  double steer_bias() const { return steer_bias_; }
  /// Checkpoints (core/state_archive.hpp): the contraction's live settings, the eq. 7.2
  /// controllers and the steering's memory. The markers are the world's.
  void archive(core::StateArchive& a);

 private:
  JellyfishSpec spec_;
  JellyfishLayout layout_;
  elastic::Body own_body_;
  elastic::Body* body_ = &own_body_;
  std::size_t first_point_ = 0, point_count_ = 0;
  std::size_t first_linear_ = 0, first_angular_ = 0;
  // Construction (§7.1), in this order: umbrella, muscles, tentacles, then rings in axisymmetric water.
  void build_umbrella(const std::vector<Vec2>& profile, double spacing);
  void build_muscles(const std::vector<Vec2>& profile, double spacing);
  void build_tentacles(int tentacle_points);
  void make_ring_jellyfish(double spacing);
  /// Adds a spring between two points of the own body, its rest length their distance now.
  int add_spring(int a, int b, double stiffness_n_per_m);
  double distance(int a, int b) const;
  /// Steering (beyond the thesis): chooses the bias once per cycle and bends the active side.
  void steer(double t);

  std::vector<RestLengthController> controllers_;
  std::vector<double> base_stiffness_;        ///< linear spring constants from the spec
  std::vector<double> base_joint_stiffness_;  ///< angular spring constants from the spec
  std::vector<double> base_rest_angle_;       ///< angular rest angles from the spec
  std::vector<int> joint_side_;               ///< −1 left, +1 right, 0 apex or tentacle
  double steer_bias_ = 0.0;
  double steer_updated_phase_ = -1e300;       ///< cycle in which the bias was last chosen
  Vec2 steer_last_heading_{};                 ///< heading when the bias was last chosen
  bool steer_has_heading_ = false;
};

/// Checks the spec; throws std::invalid_argument naming the field and its allowed range.
void validate(const JellyfishSpec& spec);

/// How many markers the slice of a (validated) spec has, worked out without building it (counts
/// as doubles: a hostile spec may ask for more than an int holds).
struct MarkerPlan {
  double segments_per_side = 0.0;  ///< umbrella springs from the aperture to the apex
  double spacing_m = 0.0;          ///< their length
  double tentacle_points = 0.0;    ///< points per tentacle beyond its root
  double markers = 0.0;            ///< every point of the slice
};
MarkerPlan plan_markers(const JellyfishSpec& spec);
/// A slice with more markers than this is refused (the dense marker-space solve alone would need
/// (2N)² × 8 bytes several times over).
inline constexpr double kMaxMarkers = 1e6;

/// Points along the half-ellipse subumbrellar profile (aperture tips at ±D/2, apex at height H),
/// evenly spaced in arc length, left tip first; before tilt and translation.
std::vector<Vec2> bell_profile(double diameter_m, double height_m, int segments_per_side);

/// Turns a built planar slice (forces per metre of depth) into rings about the vertical line
/// x = axis_x (forces of whole rings, N). With r̄ an element's mean distance from the axis (at
/// least a quarter of `spacing`, for elements on the axis):
///  * springs and joints along the bell and tentacles carry 2π r̄ times their planar force (a ring
///    element of circumference 2π r̄; the tentacles a curtain of strands around the margin);
///  * springs across the axis (the muscles) join the two points of one ring: their planar tension
///    becomes the ring's hoop tension, whose radial pull on the ring totals 2π times it;
///  * every off-axis point of `hoop_rows` (the umbrella rows) gets a hoop spring across the axis to
///    its mirror image: the bell's resistance to a change of circumference, radial force
///    2π C s (r − r₀)/r₀ with C = κ_l l_r the membrane stiffness the row's springs have and s the
///    meridional length the point stands for.
/// `partner` gives each point's mirror image; `muscles` the springs across the axis. Returns the
/// hoop springs' indices.
std::vector<int> make_rings(elastic::Body& body, double axis_x, double spacing, const std::vector<int>& partner,
                            const std::vector<std::vector<int>>& hoop_rows, const std::vector<int>& muscles,
                            double membrane_stiffness_n_per_m);

/// The arc length each point of a polyline stands for: half of each neighbouring segment (the
/// continuum model's masses, the fluid-free model's drag per unit length).
std::vector<double> arc_per_point(const std::vector<Vec2>& polyline);

/// True when two non-adjacent segments of the polyline cross (the umbrella turned inside out).
bool polyline_self_intersects(const std::vector<Vec2>& points);

}  // namespace jellysim::jellyfish
