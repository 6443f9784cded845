#include "common/fibres/laplace_p1.h"

#include "common/error.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <cmath>
#include <map>

namespace fe2 {

std::array<Vec3, 4> p1_gradients(const TetMesh& mesh, int e) {
  const auto& t = mesh.tets[e];
  Mat3 J;  // columns: the edges from vertex 0; ∇λ1..3 are the rows of J⁻¹
  for (int a = 0; a < 3; ++a) J.col(a) = mesh.nodes[t[a + 1]] - mesh.nodes[t[0]];
  const Mat3 Ji = J.inverse();
  std::array<Vec3, 4> g;
  for (int a = 0; a < 3; ++a) g[a + 1] = Ji.row(a).transpose();
  g[0] = -(g[1] + g[2] + g[3]);
  return g;
}

std::vector<double> solve_laplace_p1(const TetMesh& mesh, const std::vector<LaplaceDirichlet>& bcs,
                                     const std::string& what) {
  const int n = mesh.num_nodes();
  std::vector<char> vertex(n, 0);
  for (const auto& t : mesh.tets)
    for (int v : t) vertex[v] = 1;
  // Prescribed values; a node in two sets with different values is a contradiction.
  std::vector<double> u(n, 0.0);
  std::vector<int> set_of(n, -1);
  for (std::size_t k = 0; k < bcs.size(); ++k)
    for (int v : bcs[k].nodes) {
      if (v < 0 || v >= n || !vertex[v]) continue;
      if (set_of[v] >= 0 && u[v] != bcs[k].value)
        throw InputError(fmt::format("{}: node {} at ({}, {}, {}) lies on both '{}' (value {}) and '{}' (value {}), "
                                     "expected these surfaces to share no node",
                                     what, v, mesh.nodes[v][0], mesh.nodes[v][1], mesh.nodes[v][2],
                                     bcs[set_of[v]].set, u[v], bcs[k].set, bcs[k].value));
      set_of[v] = static_cast<int>(k);
      u[v] = bcs[k].value;
    }
  std::vector<int> dof(n, -1);
  int nf = 0;
  for (int v = 0; v < n; ++v)
    if (vertex[v] && set_of[v] < 0) dof[v] = nf++;
  if (nf == 0) return u;

  // K_ff u_f = −K_fd u_d, assembled element by element: K_ab = V ∇λ_a·∇λ_b.
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf);
  for (int e = 0; e < mesh.num_tets(); ++e) {
    const auto g = p1_gradients(mesh, e);
    const double V = std::abs(tet_signed_volume(mesh, e));
    const auto& t = mesh.tets[e];
    for (int a = 0; a < 4; ++a) {
      const int i = dof[t[a]];
      if (i < 0) continue;
      for (int b = 0; b < 4; ++b) {
        const double k = V * g[a].dot(g[b]);
        const int j = dof[t[b]];
        if (j >= 0)
          trip.emplace_back(i, j, k);
        else
          rhs[i] -= k * u[t[b]];
      }
    }
  }
  Eigen::SparseMatrix<double> K(nf, nf);
  K.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(K);
  // A part of the mesh without Dirichlet nodes makes K singular (zero pivot).
  const bool ok = ldlt.info() == Eigen::Success &&
                  (ldlt.vectorD().array() > 1e-12 * ldlt.vectorD().cwiseAbs().maxCoeff()).all();
  if (!ok)
    throw InputError(fmt::format("{}: the Laplace problem is singular (a part of the mesh touches none of the "
                                 "surfaces {}), expected every part of the wall to reach them",
                                 what, [&] {
                                   std::string s;
                                   for (const auto& b : bcs) s += (s.empty() ? "'" : ", '") + b.set + "'";
                                   return s;
                                 }()));
  const Eigen::VectorXd x = ldlt.solve(rhs);
  for (int v = 0; v < n; ++v)
    if (dof[v] >= 0) u[v] = x[dof[v]];
  return u;
}

}  // namespace fe2
