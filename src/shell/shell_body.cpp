#include "jellysim/shell/shell_body.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/QR>

#include "shell_elements.hpp"

namespace jellysim::shell {

Vector stack(const std::vector<Vec3>& points) {
  Vector x(3 * static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) x.segment<3>(3 * static_cast<Eigen::Index>(i)) = points[i];
  return x;
}

std::vector<Vec3> unstack(const Vector& x) {
  std::vector<Vec3> out(static_cast<std::size_t>(x.size() / 3));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = vertex(x, static_cast<int>(i));
  return out;
}

double dihedral_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 edge = x1 - x0;
  const Vec3 na = edge.cross(x2 - x0), nb = (x0 - x1).cross(x3 - x1);
  return std::atan2(na.cross(nb).dot(edge) / edge.norm(), na.dot(nb));
}

namespace {

/// The face's rest edges in its own 2D frame (e₁ along x1 − x0): D_m = [[|u|, w·e₁], [0, h]].
Eigen::Matrix2d rest_frame(const Vec3& x0, const Vec3& x1, const Vec3& x2, Vec3& e1, Vec3& e2) {
  const Vec3 u = x1 - x0, w = x2 - x0;
  e1 = u.normalized();
  const Vec3 across = w - w.dot(e1) * e1;
  e2 = across.normalized();
  Eigen::Matrix2d dm;
  dm << u.norm(), w.dot(e1), 0.0, across.norm();
  return dm;
}

MembraneElement make_membrane(const TriangleMesh& mesh, const std::array<int, 3>& t, const ShellMaterial& m) {
  const auto& p = mesh.vertices;
  Vec3 e1, e2;
  const Eigen::Matrix2d dm = rest_frame(p[static_cast<std::size_t>(t[0])], p[static_cast<std::size_t>(t[1])],
                                        p[static_cast<std::size_t>(t[2])], e1, e2);
  if (!(std::abs(dm.determinant()) > 0)) throw std::invalid_argument("make_shell_body: a degenerate triangle");
  MembraneElement e;
  e.v = t;
  e.rest_inverse = dm.inverse();
  e.rest_area_m2 = 0.5 * dm.determinant();
  e.mu_n_per_m = m.membrane_mu_n_per_m();
  e.lambda_n_per_m = m.membrane_lambda_n_per_m();
  return e;
}

HingeElement make_hinge(const TriangleMesh& mesh, const Hinge& h, double bending_n_m) {
  auto at = [&](int k) { return mesh.vertices[static_cast<std::size_t>(h.v[static_cast<std::size_t>(k)])]; };
  HingeElement e;
  e.v = h.v;
  e.rest_angle_rad = dihedral_angle(at(0), at(1), at(2), at(3));
  // k_e = D |ē|² / (2Ā_e) (Discrete Shells' 3|ē|²/Ā_e weight with the constant D/6): a cylinder on
  // an equilateral mesh stores ½Dκ² per area (docs/three-d.md).
  const double area = triangle_area(at(0), at(1), at(2)) + triangle_area(at(1), at(0), at(3));
  e.stiffness_n_m = 0.5 * bending_n_m * (at(1) - at(0)).squaredNorm() / area;
  return e;
}

/// The hinge row of the curvature fit: θ_i as a linear function of h = (H_xx, H_xy, H_yy) for the
/// deflection w = ½ xᵀ H x of the flat diamond (the face in its own 2D frame, the neighbour's far
/// vertex `q` unfolded across the edge a → b), by central differences of the hinge angle itself
/// (so the sign convention is dihedral_angle's); exact to about 1e-12 for a linear map.
Eigen::RowVector3d hinge_row(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p,
                             const Eigen::Vector2d& q) {
  const double scale = std::max({a.norm(), b.norm(), p.norm(), q.norm()});
  const double eps = 2e-6 / (scale * scale);  // lifts of about 1e-6 of the face's size
  auto lift = [](const Eigen::Vector2d& x, const Eigen::Vector3d& h, double s) {
    return Vec3(x.x(), x.y(), s * (0.5 * h(0) * x.x() * x.x() + h(1) * x.x() * x.y() + 0.5 * h(2) * x.y() * x.y()));
  };
  Eigen::RowVector3d row;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d h = Eigen::Vector3d::Unit(k);
    auto theta = [&](double s) { return dihedral_angle(lift(a, h, s), lift(b, h, s), lift(p, h, s), lift(q, h, s)); };
    row(k) = (theta(eps) - theta(-eps)) / (2.0 * eps);
  }
  return row;
}

/// The free edge's row: a bending moment of zero across the edge, H_nn + ν H_tt = 0.
Eigen::RowVector3d free_edge_row(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double nu) {
  const Eigen::Vector2d t = (b - a).normalized(), n(-t.y(), t.x());
  return {n.x() * n.x() + nu * t.x() * t.x(), 2.0 * (n.x() * n.y() + nu * t.x() * t.y()), n.y() * n.y() + nu * t.y() * t.y()};
}

/// The far vertex q of the neighbour across the edge a → b, unfolded into the face's plane on the
/// side away from p, from its rest distances (intrinsic: the same on a curved rest surface).
Eigen::Vector2d unfold(const Vec3& a3, const Vec3& b3, const Vec3& q3, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& p) {
  const Vec3 e = b3 - a3;
  const double s = (q3 - a3).dot(e) / e.squaredNorm();
  const double height = (q3 - a3 - s * e).norm();
  Eigen::Vector2d n(-(b - a).y(), (b - a).x());
  n.normalize();
  if ((p - a).dot(n) > 0) n = -n;
  return a + s * (b - a) + height * n;
}

/// The face's bending: h = (H_xx, H_xy, H_yy) = M Δθ with M the mid-edge map, or (fitted) M = N⁻¹
/// with N's rows hinge_row, clamped_row or free_edge_row; W = ½ A D hᵀ B h with B the quadratic
/// form of (tr H)² − 2(1 − ν) det H, so G = A D Mᵀ B M on the hinge rows.
/// The clamped edge's row: the element measures twice the face's turn about the held edge a → b,
/// −2 (w_p − w_foot) / h for small slopes (dihedral_angle's sign: raising the far vertex turns the
/// face negatively), w_foot the deflection interpolated along the edge at the foot of p and h the
/// distance of p from the edge; for w = ½ xᵀ H x this is linear in h = (H_xx, H_xy, H_yy).
Eigen::RowVector3d clamped_row(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d e = b - a;
  const double s = (p - a).dot(e) / e.squaredNorm(), h = (p - a - s * e).norm();
  auto basis = [](const Eigen::Vector2d& x) { return Eigen::RowVector3d(0.5 * x.x() * x.x(), x.x() * x.y(), 0.5 * x.y() * x.y()); };
  return -2.0 * (basis(p) - (1.0 - s) * basis(a) - s * basis(b)) / h;
}

/// The rest position of x_p mirrored across the line a–b.
Vec3 mirrored(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 e = (b - a).normalized();
  const Vec3 foot = a + (p - a).dot(e) * e;
  return 2.0 * foot - p;
}

/// The face's bending: h = (H_xx, H_xy, H_yy) = M Δθ with M the mid-edge map, or (fitted) M = N⁻¹
/// with N's rows hinge_row, clamped_row or free_edge_row; W = ½ A D hᵀ B h with B the quadratic
/// form of (tr H)² − 2(1 − ν) det H, so G = A D Mᵀ B M on the hinge rows.
/// The mid-edge map (Oñate & Zárate's Basic Plate Triangle): ∫_t H = ∮ ∇w ⊗ n with the slope at each
/// edge's midpoint the average of the two faces', so H = (1/2A) Σ_i |e_i| [∂w/∂n]_i n_i n_iᵀ over the
/// face's edges (the face's own gradient drops out, Σ |e_i| n_i = 0); [∂w/∂n] = −θ for small slopes.
/// A free edge has no jump; a clamped one the jump to the face's mirror image.
Eigen::Matrix3d midedge_map(const std::array<Eigen::Vector2d, 3>& p, const std::array<EdgeKind, 3>& kind) {
  const double area = 0.5 * std::abs((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
  Eigen::Matrix3d map = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    if (kind[i] == EdgeKind::free) continue;
    const Eigen::Vector2d e = p[(i + 2) % 3] - p[(i + 1) % 3];
    const Eigen::Vector2d n = Eigen::Vector2d(-e.y(), e.x()).normalized();
    const double c = -e.norm() / (2.0 * area);  // dihedral_angle is minus the slope jump
    map.col(static_cast<Eigen::Index>(i)) << c * n.x() * n.x(), c * n.x() * n.y(), c * n.y() * n.y();
  }
  return map;
}

BendingTriangle make_bending_triangle(const TriangleMesh& mesh, const std::array<int, 3>& t, const std::array<int, 3>& across,
                                      const std::array<bool, 3>& clamped, const ShellMaterial& m, bool midedge) {
  auto at = [&](int v) { return mesh.vertices[static_cast<std::size_t>(v)]; };
  Vec3 e1, e2;
  const Eigen::Matrix2d dm = rest_frame(at(t[0]), at(t[1]), at(t[2]), e1, e2);
  const std::array<Eigen::Vector2d, 3> p{Eigen::Vector2d::Zero(), dm.col(0), dm.col(1)};
  BendingTriangle e;
  Eigen::Matrix3d rows;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t a = (i + 1) % 3, b = (i + 2) % 3;
    const auto r = static_cast<Eigen::Index>(i);
    e.v[i] = t[i];
    e.v[3 + i] = across[i] >= 0 ? across[i] : t[i];
    e.edge[i] = across[i] >= 0 ? EdgeKind::hinge : clamped[i] ? EdgeKind::clamped : EdgeKind::free;
    if (e.edge[i] == EdgeKind::free) {
      rows.row(r) = free_edge_row(p[a], p[b], m.poisson_ratio);
      continue;
    }
    if (e.edge[i] == EdgeKind::clamped) e.mirror[i] = mirrored(at(t[a]), at(t[b]), at(t[i]));
    const Vec3 far = e.edge[i] == EdgeKind::clamped ? e.mirror[i] : at(across[i]);
    rows.row(r) = e.edge[i] == EdgeKind::clamped ? clamped_row(p[a], p[b], p[i])
                                                 : hinge_row(p[a], p[b], p[i], unfold(at(t[a]), at(t[b]), far, p[a], p[b], p[i]));
    e.rest_angle_rad[i] = (e.edge[i] == EdgeKind::clamped ? 2.0 : 1.0) * dihedral_angle(at(t[a]), at(t[b]), at(t[i]), far);
  }
  const double nu = m.poisson_ratio;
  Eigen::Matrix3d B;
  B << 1.0, 0.0, nu, 0.0, 2.0 * (1.0 - nu), 0.0, nu, 0.0, 1.0;
  const Eigen::Matrix3d inv = midedge ? midedge_map(p, e.edge) : Eigen::Matrix3d(rows.completeOrthogonalDecomposition().pseudoInverse());
  e.G = 0.5 * dm.determinant() * m.bending_n_m() * inv.transpose() * B * inv;
  for (int i = 0; i < 3; ++i)
    if (e.edge[static_cast<std::size_t>(i)] == EdgeKind::free) e.G.row(i).setZero(), e.G.col(i).setZero();
  return e;
}

/// For every face, the vertex across each edge (opposite vertex i), −1 on the boundary.
std::vector<std::array<int, 3>> across_edges(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, int> opposite;  // directed edge → the vertex of its face across it
  for (const auto& t : mesh.triangles)
    for (std::size_t i = 0; i < 3; ++i) opposite[{t[(i + 1) % 3], t[(i + 2) % 3]}] = t[i];
  std::vector<std::array<int, 3>> out;
  for (const auto& t : mesh.triangles) {
    std::array<int, 3> a{-1, -1, -1};
    for (std::size_t i = 0; i < 3; ++i) {
      const auto it = opposite.find({t[(i + 2) % 3], t[(i + 1) % 3]});
      if (it != opposite.end()) a[i] = it->second;
    }
    out.push_back(a);
  }
  return out;
}

}  // namespace

ShellBody make_shell_body(const TriangleMesh& mesh, const ShellMaterial& material, BendingModel bending,
                          const std::vector<int>& clamped) {
  validate(material);
  ShellBody body;
  const std::vector<double> area = vertex_areas(mesh);
  for (double a : area) body.mass_kg.push_back(material.mass_per_area_kg_per_m2() * a);
  for (const auto& t : mesh.triangles) body.membranes.push_back(make_membrane(mesh, t, material));
  if (bending == BendingModel::hinge) {
    for (const Hinge& h : interior_hinges(mesh)) body.hinges.push_back(make_hinge(mesh, h, material.bending_n_m()));
    return body;
  }
  const auto across = across_edges(mesh);
  auto held = [&](int v) { return std::binary_search(clamped.begin(), clamped.end(), v); };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    std::array<bool, 3> edge_clamped{};
    for (std::size_t i = 0; i < 3; ++i) edge_clamped[i] = held(t[(i + 1) % 3]) && held(t[(i + 2) % 3]);
    body.bending_triangles.push_back(make_bending_triangle(mesh, t, across[f], edge_clamped, material, bending == BendingModel::midedge));
  }
  return body;
}

FibreElement make_fibre(const Vec3& xa, const Vec3& xb, const Vec3& xc, std::array<int, 3> v, const Vec3& direction,
                        double stiffness_n_per_m) {
  Vec3 e1, e2;
  const Eigen::Matrix2d dm = rest_frame(xa, xb, xc, e1, e2);
  const Eigen::Vector2d a = Eigen::Vector2d(direction.dot(e1), direction.dot(e2)).normalized();
  const Eigen::Vector2d w = dm.inverse() * a;  // F a = (x_b − x_a) w₀ + (x_c − x_a) w₁
  FibreElement f;
  f.v = v;
  f.weights = {-w(0) - w(1), w(0), w(1)};
  f.rest_area_m2 = 0.5 * dm.determinant();
  f.stiffness_n_per_m = stiffness_n_per_m;
  return f;
}

namespace {

template <std::size_t N>
detail::Points<N> gather(const Vector& x, const std::array<int, N>& idx) {
  detail::Points<N> p;
  for (std::size_t i = 0; i < N; ++i) p[i] = vertex(x, idx[i]);
  return p;
}

std::array<int, 2> indices(const RodSegment& e) { return {e.a, e.b}; }
std::array<int, 4> indices(const RodJoint& e) { return {e.a[0], e.a[1], e.b, e.c}; }
template <class E>
auto indices(const E& e) { return e.v; }

/// Calls visit(element, its vertex indices, its force function) for every element of the body.
template <class Visit>
void visit_elements(const ShellBody& b, Visit&& visit) {
  for (const auto& e : b.membranes) visit(e, indices(e), detail::membrane);
  for (const auto& e : b.hinges) visit(e, indices(e), detail::hinge);
  for (const auto& e : b.bending_triangles) visit(e, indices(e), detail::bending_triangle);
  for (const auto& e : b.fibres) visit(e, indices(e), detail::fibre);
  for (const auto& e : b.rod_segments) visit(e, indices(e), detail::rod_segment);
  for (const auto& e : b.rod_joints) visit(e, indices(e), detail::rod_joint);
}

}  // namespace

double elastic_energy(const ShellBody& body, const Vector& x) {
  double w = 0.0;
  visit_elements(body, [&](const auto& e, const auto& idx, auto fn) {
    auto p = gather(x, idx);
    decltype(p) f;
    f.fill(Vec3::Zero());
    w += fn(e, p, f);
  });
  return w;
}

void add_elastic_forces(const ShellBody& body, const Vector& x, Vector& force) {
  visit_elements(body, [&](const auto& e, const auto& idx, auto fn) {
    auto p = gather(x, idx);
    decltype(p) f;
    f.fill(Vec3::Zero());
    fn(e, p, f);
    for (std::size_t i = 0; i < idx.size(); ++i) force.segment<3>(3 * static_cast<Eigen::Index>(idx[i])) += f[i];
  });
}

namespace {

/// Central-difference Hessian of one element, −∂f_i/∂x_j, symmetrised, scattered as triplets.
template <class E, std::size_t N, class Fn>
void element_hessian(const E& e, const std::array<int, N>& idx, const Vector& x, Fn fn,
                     std::vector<Eigen::Triplet<double>>& out) {
  const detail::Points<N> p = gather(x, idx);
  double size = 0.0;
  for (std::size_t i = 1; i < N; ++i) size = std::max(size, (p[i] - p[0]).norm());
  const double h = 1e-6 * size;
  Eigen::Matrix<double, 3 * N, 3 * N> k;
  for (std::size_t j = 0; j < 3 * N; ++j) {
    detail::Points<N> plus = p, minus = p, fp, fm;
    plus[j / 3](static_cast<Eigen::Index>(j % 3)) += h;
    minus[j / 3](static_cast<Eigen::Index>(j % 3)) -= h;
    fp.fill(Vec3::Zero());
    fm.fill(Vec3::Zero());
    fn(e, plus, fp);
    fn(e, minus, fm);
    for (std::size_t i = 0; i < 3 * N; ++i)
      k(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          -(fp[i / 3](static_cast<Eigen::Index>(i % 3)) - fm[i / 3](static_cast<Eigen::Index>(i % 3))) / (2.0 * h);
  }
  const Eigen::Matrix<double, 3 * N, 3 * N> sym = 0.5 * (k + k.transpose());
  for (std::size_t i = 0; i < 3 * N; ++i)
    for (std::size_t j = 0; j < 3 * N; ++j)
      out.emplace_back(3 * idx[i / 3] + static_cast<int>(i % 3), 3 * idx[j / 3] + static_cast<int>(j % 3),
                       sym(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
}

double characteristic_length(const ShellBody& body) {
  if (!body.membranes.empty()) return std::sqrt(body.membranes.front().rest_area_m2);
  if (!body.rod_segments.empty()) return body.rod_segments.front().rest_length_m;
  return 1.0;
}

}  // namespace

SparseMatrix stiffness_matrix(const ShellBody& body, const Vector& x) {
  std::vector<Eigen::Triplet<double>> triplets;
  visit_elements(body, [&](const auto& e, const auto& idx, auto fn) { element_hessian(e, idx, x, fn, triplets); });
  SparseMatrix k(x.size(), x.size());
  k.setFromTriplets(triplets.begin(), triplets.end());
  return k;
}

Vector stiffness_times(const ShellBody& body, const Vector& x, const Vector& v) {
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0)) return Vector::Zero(x.size());
  const double eps = 1e-6 * characteristic_length(body) / largest;
  Vector fp = Vector::Zero(x.size()), fm = Vector::Zero(x.size());
  add_elastic_forces(body, x + eps * v, fp);
  add_elastic_forces(body, x - eps * v, fm);
  return -(fp - fm) / (2.0 * eps);
}

}  // namespace jellysim::shell
