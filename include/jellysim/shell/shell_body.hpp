#pragma once
// The elastic shell as a sum of element energies over a triangulated surface (issue 40 part 3,
// docs/three-d.md "Part 3"), each built from material quantities so that refining the mesh
// describes the same body:
//  * membrane: one constant-strain triangle per face (linear FEM), a compressible neo-Hookean
//    membrane with the plane-stress Lamé constants (μh, λh of ShellMaterial), per rest area
//      W = A₀ [ ½μh (tr C − 2) − μh ln J + ½λh (ln J)² ],  C = FᵀF, J = √det C,
//    F the 3×2 deformation gradient of the face; it is linear plane-stress elasticity (E, ν) for
//    small strains and stays finite however far the muscles compress it;
//  * bending, from the hinge angles θ_e (the signed dihedral angles at interior edges) of
//    Grinspun, Hirani, Desbrun & Schröder, "Discrete Shells" (SCA 2003), one of three ways
//    (BendingModel, docs/three-d.md gives the derivations and the measured mesh-dependence):
//     - midedge (the default): per face a curvature tensor H_t (2×2, in the face's frame) from the
//       slopes at its edges' midpoints averaged between the two faces there, the Basic Plate
//       Triangle of Oñate & Zárate ("Rotation-free triangular plate and shell elements", IJNME 47,
//       2000): H_t = −(1/2A_t) Σ_i |e_i| θ_i n_i n_iᵀ (n_i the edge's in-plane normal), and
//       Kirchhoff's energy W_t = ½ D A_t [(tr H)² − 2(1 − ν) det H] = ½ Δθᵀ G_t Δθ, Δθ = θ − θ̄;
//       a free edge contributes no slope jump; a clamped edge (both its vertices held) the hinge
//       to the face's mirror image, twice the face's turn about the edge from its rest plane;
//     - fitted: the same energy with H_t fitted so that the face's three hinge angles are exact
//       for every quadratic deflection (the free edge's row H_nn + ν H_tt = 0): exact energies for
//       quadratics on any mesh, but its forces are not (measured in the docs);
//     - hinge: Discrete Shells' energy W = k_e (θ_e − θ̄_e)², k_e = D |ē|² / (2 Ā_e) (Ā_e the rest
//       area of the edge's two faces): exact for cylinders on equilateral meshes, but its Poisson
//       ratio is −1/3 there whatever ν, and other meshes shift it;
//  * mass: ρh times a third of each face's rest area, lumped at the vertices;
//  * fibres (muscles): per face a tension along a rest direction a, W = ½ k A₀ (|F a| − r)², k the
//    layer's tension per unit width per unit strain (N/m), r its rest stretch (the contraction);
//  * rods (tentacles): segments W = ½ (EA / l₀)(l − l₀)² and joints W = k (1 − cos φ), φ the turning
//    angle, k = EI / l̄ (≈ ½ (EI/l̄) φ²: the slice's joint B / l̄).
// Positions are stacked x₀, y₀, z₀, x₁, … (m); forces in N.
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "jellysim/shell/shell_material.hpp"
#include "jellysim/shell/triangle_mesh.hpp"

namespace jellysim::shell {

using Vector = Eigen::VectorXd;
using SparseMatrix = Eigen::SparseMatrix<double>;

struct MembraneElement {
  std::array<int, 3> v{};
  Eigen::Matrix2d rest_inverse = Eigen::Matrix2d::Identity();  ///< D_m⁻¹, the rest edges in the face's own 2D frame
  double rest_area_m2 = 0.0;
  double mu_n_per_m = 0.0;       ///< μh
  double lambda_n_per_m = 0.0;   ///< λh (plane stress)
};

struct HingeElement {
  std::array<int, 4> v{};        ///< edge v0 → v1, faces (v0, v1, v2) and (v1, v0, v3)
  double rest_angle_rad = 0.0;
  double stiffness_n_m = 0.0;    ///< k_e
};

enum class EdgeKind { hinge, free, clamped };

/// A face and the three vertices across its edges: v[0..2] the face, v[3 + i] across the edge
/// opposite v[i] (v[i] itself where that edge is on the boundary).
struct BendingTriangle {
  std::array<int, 6> v{};
  std::array<EdgeKind, 3> edge{EdgeKind::hinge, EdgeKind::hinge, EdgeKind::hinge};
  std::array<Vec3, 3> mirror{Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  ///< clamped edges: the face's far vertex mirrored at rest
  std::array<double, 3> rest_angle_rad{};
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();  ///< W = ½ Δθᵀ G Δθ (N·m)
};

enum class BendingModel { midedge, fitted, hinge };

struct FibreElement {
  std::array<int, 3> v{};
  std::array<double, 3> weights{};  ///< F a = Σ weights[i] x_i
  double rest_area_m2 = 0.0;
  double stiffness_n_per_m = 0.0;   ///< tension per unit width per unit strain
  double rest_stretch = 1.0;        ///< r: 1 relaxed, γ fully contracted (eq. 7.5)
};

struct RodSegment {
  int a = 0, b = 0;
  double axial_stiffness_n = 0.0;   ///< EA
  double rest_length_m = 0.0;
};

/// The turning angle at b between the segment from the point a (a weighted pair of vertices) to b
/// and the segment b → c.
struct RodJoint {
  std::array<int, 2> a{};
  std::array<double, 2> a_weights{1.0, 0.0};
  int b = 0, c = 0;
  double stiffness_n_m = 0.0;       ///< k of W = k (1 − cos φ)
};

struct ShellBody {
  std::vector<double> mass_kg;      ///< per vertex
  std::vector<MembraneElement> membranes;
  std::vector<HingeElement> hinges;                  ///< BendingModel::hinge
  std::vector<BendingTriangle> bending_triangles;    ///< BendingModel::midedge and ::fitted
  std::vector<FibreElement> fibres;
  std::vector<RodSegment> rod_segments;
  std::vector<RodJoint> rod_joints;
  std::size_t vertex_count() const { return mass_kg.size(); }
};

/// Stacks positions into one vector (3 per vertex) and back.
Vector stack(const std::vector<Vec3>& points);
std::vector<Vec3> unstack(const Vector& x);
inline Vec3 vertex(const Vector& x, int i) { return x.segment<3>(3 * static_cast<Eigen::Index>(i)); }

/// A membrane element and the bending of every face (or every interior edge: BendingModel::hinge)
/// of `mesh`, rest state = the mesh, lumped masses ρh A/3 (validates the material). Boundary edges
/// with both vertices in `clamped` (ascending; the caller holds those vertices) are clamped edges
/// of the face-wise bending, the others free.
ShellBody make_shell_body(const TriangleMesh& mesh, const ShellMaterial& material,
                          BendingModel bending = BendingModel::midedge, const std::vector<int>& clamped = {});
/// A fibre on face (a, b, c) at rest positions along `direction` (projected into the face).
FibreElement make_fibre(const Vec3& xa, const Vec3& xb, const Vec3& xc, std::array<int, 3> v, const Vec3& direction,
                        double stiffness_n_per_m);

/// θ: the signed dihedral angle at the edge x0 → x1 between the faces (x0, x1, x2) and (x1, x0, x3),
/// 0 when flat, in (−π, π].
double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

/// Σ element energies (J) at positions x.
double elastic_energy(const ShellBody& body, const Vector& x);
/// Adds the elastic forces −∂W/∂x (N) at positions x to f (sized 3 × vertices).
void add_elastic_forces(const ShellBody& body, const Vector& x, Vector& f);
/// K = ∂²W/∂x² (N/m), symmetric, assembled from element Hessians taken by central differences of
/// each element's analytic forces (step 10⁻⁶ of the element's size: relative error about 1e-9).
SparseMatrix stiffness_matrix(const ShellBody& body, const Vector& x);
/// K v without assembling K: −(f(x + εv) − f(x − εv)) / 2ε, ε = 1e-7 · max|x| / max|v|.
Vector stiffness_times(const ShellBody& body, const Vector& x, const Vector& v);

}  // namespace jellysim::shell
