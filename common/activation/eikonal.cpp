#include "common/activation/eikonal.h"

#include "common/error.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace fe2 {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double metric_norm(const Vec3& d, const Mat3& M) { return std::sqrt(std::max(0.0, d.dot(M * d))); }

/// Vertex -> the tets that hold it, ascending (compressed rows).
struct VertexTets {
  std::vector<int> start, tets;
  explicit VertexTets(const TetMesh& mesh) : start(mesh.nodes.size() + 1, 0) {
    for (const auto& t : mesh.tets)
      for (int v : t) ++start[v + 1];
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    tets.resize(start.back());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e = 0; e < mesh.num_tets(); ++e)  // ascending e: each row comes out sorted
      for (int v : mesh.tets[e]) tets[fill[v]++] = e;
  }
  int count(int v) const { return start[v + 1] - start[v]; }
};

}  // namespace

Mat3 conduction_metric(const Mat3& Q, double v_fibre, double v_sheet, double v_normal) {
  const Vec3 v2(v_fibre * v_fibre, v_sheet * v_sheet, v_normal * v_normal);
  return Q * v2.asDiagonal() * Q.transpose();
}

double eikonal_simplex_update(const Vec3& x, const Vec3* y, const double* t, int k, const Mat3& M) {
  if (k == 1) return t[0] + metric_norm(x - y[0], M);
  // Points y0 + E μ of the simplex's plane (E: edges from y0), times t0 + δ·μ.
  // Stationarity of f(μ) = t0 + δ·μ + ‖r − Eμ‖_M (r = x − y0) gives, with G = EᵀME,
  // a = G⁻¹EᵀMr (the projection of x), b = G⁻¹δ, q = δᵀb and h = ‖r − Ea‖_M (the
  // distance from x to the plane): s = ‖r − Eμ‖_M = h / sqrt(1 − q), μ = a − s b and
  // f = t0 + δᵀa + h sqrt(1 − q). It is the minimum when q < 1 (the front is slower
  // along the simplex than the medium allows) and μ lies in the simplex; else the
  // minimum is on the boundary (f is convex).
  const int m = k - 1;
  Eigen::Matrix<double, 3, 2> E = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();
  for (int i = 0; i < m; ++i) {
    E.col(i) = y[i + 1] - y[0];
    delta[i] = t[i + 1] - t[0];
  }
  const Vec3 r = x - y[0];
  const Eigen::Matrix<double, 3, 2> ME = M * E;
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  bool solved = false;
  if (m == 1) {
    const double g = E.col(0).dot(ME.col(0));
    if (g > 0) {
      a[0] = ME.col(0).dot(r) / g;
      b[0] = delta[0] / g;
      solved = true;
    }
  } else {
    const double g00 = E.col(0).dot(ME.col(0)), g01 = E.col(0).dot(ME.col(1)), g11 = E.col(1).dot(ME.col(1));
    const double det = g00 * g11 - g01 * g01;
    if (det > 1e-14 * g00 * g11) {  // not a sliver face
      const double w0 = ME.col(0).dot(r), w1 = ME.col(1).dot(r);
      a = Eigen::Vector2d(g11 * w0 - g01 * w1, g00 * w1 - g01 * w0) / det;
      b = Eigen::Vector2d(g11 * delta[0] - g01 * delta[1], g00 * delta[1] - g01 * delta[0]) / det;
      solved = true;
    }
  }
  if (solved) {
    const double q = delta.dot(b);
    const Vec3 foot = r - E * a;
    const double h2 = foot.dot(M * foot);
    if (q < 1 && h2 > 0) {
      const double s = std::sqrt(h2 / (1 - q));
      const Eigen::Vector2d mu = a - s * b;
      bool inside = true;
      double sum = 0;
      for (int i = 0; i < m; ++i) {
        inside = inside && mu[i] >= 0;
        sum += mu[i];
      }
      if (inside && sum <= 1) return t[0] + delta.dot(a) + std::sqrt(h2 * (1 - q));  // unused entries are 0
    }
  }
  // The boundary: each facet (drop one point), down to the vertices.
  double best = kInf;
  for (int drop = 0; drop < k; ++drop) {
    Vec3 ys[2];
    double ts[2];
    int n = 0;
    for (int i = 0; i < k; ++i)
      if (i != drop) ys[n] = y[i], ts[n++] = t[i];
    best = std::min(best, eikonal_simplex_update(x, ys, ts, n, M));
  }
  return best;
}

std::vector<double> solve_eikonal(const TetMesh& mesh, const std::vector<Mat3>& metric,
                                  const std::vector<EikonalSource>& sources, const EikonalOptions& opt,
                                  EikonalStats* stats) {
  const int nn = mesh.num_nodes(), ne = mesh.num_tets();
  FE2_CHECK(static_cast<int>(metric.size()) == ne, "eikonal: {} metrics for {} tets", metric.size(), ne);
  // M_e = D_e⁻¹, after checking D_e is symmetric positive definite.
  std::vector<Mat3> M(ne);
  double slowest = 0;  // an upper bound of 1/v over the mesh, for the time scale
  for (int e = 0; e < ne; ++e) {
    const Mat3& D = metric[e];
    const Eigen::LLT<Mat3> llt(D);
    FE2_CHECK(D.allFinite() && (D - D.transpose()).norm() <= 1e-12 * D.norm() && llt.info() == Eigen::Success &&
                  D.diagonal().minCoeff() > 0,
              "eikonal: the conduction metric of element {} is not symmetric positive definite", e);
    M[e] = llt.solve(Mat3::Identity());
    M[e] = 0.5 * (M[e] + M[e].transpose()).eval();
    slowest = std::max(slowest, std::sqrt(M[e].trace()));
  }
  const VertexTets adj(mesh);

  std::vector<double> t(nn, kInf);
  std::vector<char> fixed(nn, 0);
  double scale = 0;
  for (const EikonalSource& s : sources) {
    if (s.vertex < 0 || s.vertex >= nn || adj.count(s.vertex) == 0)
      throw InputError(fmt::format("eikonal source at node {}: not a vertex of the mesh's tets (nodes 0..{}), "
                                   "expected a tet vertex",
                                   s.vertex, nn - 1));
    FE2_CHECK(std::isfinite(s.time), "eikonal source at vertex {}: time {}", s.vertex, s.time);
    t[s.vertex] = std::min(t[s.vertex], s.time);
    fixed[s.vertex] = 1;
    scale = std::max(scale, std::abs(s.time));
  }
  if (sources.empty()) throw InputError("eikonal: no source vertices, expected at least one");
  Vec3 lo = mesh.nodes.empty() ? Vec3::Zero() : mesh.nodes[0], hi = lo;
  for (const Vec3& p : mesh.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  scale += (hi - lo).norm() * slowest;  // no time exceeds this scale by much
  if (!(scale > 0)) scale = 1;
  // A drop smaller than this is round-off: refusing it keeps two nearly equal paths
  // from trading ulps forever.
  const double tol = 1e-14 * scale;

  // Min-heap on (time, vertex): the pair order makes the sweep deterministic.
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (int v = 0; v < nn; ++v)
    if (fixed[v]) heap.emplace(t[v], v);

  long long nv = 0;
  for (int v = 0; v < nn; ++v) nv += adj.count(v) > 0;
  const long long cap = static_cast<long long>(opt.max_pops_per_vertex) * std::max(1LL, nv);
  EikonalStats st;
  while (!heap.empty()) {
    const auto [tv, v] = heap.top();
    heap.pop();
    if (tv != t[v]) continue;  // a stale entry: v dropped again after this push
    if (++st.pops > cap)
      throw NumericalError(fmt::format("eikonal solve did not converge: {} vertex evaluations for {} vertices "
                                       "(cap {} per vertex), expected a few per vertex",
                                       st.pops - 1, nv, opt.max_pops_per_vertex));
    for (int i = adj.start[v]; i < adj.start[v + 1]; ++i) {
      const int e = adj.tets[i];
      const auto& tet = mesh.tets[e];
      for (int j = 0; j < 4; ++j) {
        const int w = tet[j];
        if (w == v || fixed[w]) continue;
        Vec3 y[3];
        double ty[3];
        int k = 0;
        for (int o = 0; o < 4; ++o)
          if (o != j && std::isfinite(t[tet[o]])) y[k] = mesh.nodes[tet[o]], ty[k++] = t[tet[o]];
        const double cand = eikonal_simplex_update(mesh.nodes[w], y, ty, k, M[e]);
        const double old = t[w];
        if (cand < old && (old == kInf || old - cand > tol * (1.0 + std::abs(old) / scale))) {
          t[w] = cand;
          ++st.updates;
          heap.emplace(cand, w);
        }
      }
    }
  }

  long long unreached = 0;
  int first = -1;
  for (int v = 0; v < nn; ++v)
    if (adj.count(v) > 0 && !std::isfinite(t[v])) {
      if (first < 0) first = v;
      ++unreached;
    }
  if (unreached > 0)
    throw InputError(fmt::format("eikonal: {} of {} mesh vertices are not reachable from any source (e.g. node {} "
                                 "at ({}, {}, {})), expected every part of the mesh to touch a source",
                                 unreached, nv, first, mesh.nodes[first][0], mesh.nodes[first][1],
                                 mesh.nodes[first][2]));
  for (int v = 0; v < nn; ++v)
    if (adj.count(v) == 0) t[v] = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [edge, node] : mesh.edge_nodes) t[node] = 0.5 * (t[edge.first] + t[edge.second]);
  if (stats) *stats = st;
  return t;
}

}  // namespace fe2
