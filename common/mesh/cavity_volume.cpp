#include "common/mesh/cavity_volume.h"

#include "common/error.h"
#include "common/spec/SpecNode.h"

#include <algorithm>
#include <array>
#include <map>

namespace fe2 {

namespace {

// Dunavant's 6-point rule on the reference triangle, exact for degree 4: {ξ, η, weight},
// weights summing to 1 (times the area 1/2).
constexpr double kA1 = 0.445948490915964886, kW1 = 0.223381589678011466;
constexpr double kA2 = 0.091576213509770743, kW2 = 0.109951743655321868;
constexpr std::array<std::array<double, 3>, 6> kPoints = {{{kA1, kA1, kW1},
                                                           {1 - 2 * kA1, kA1, kW1},
                                                           {kA1, 1 - 2 * kA1, kW1},
                                                           {kA2, kA2, kW2},
                                                           {1 - 2 * kA2, kA2, kW2},
                                                           {kA2, 1 - 2 * kA2, kW2}}};

// Shape functions of the 3- or 6-node triangle (vertices, then edges 01, 12, 20) and
// their ξ and η derivatives at (ξ, η).
struct Shape {
  std::array<double, 6> N{}, dxi{}, deta{};
};

Shape shape(int n, double xi, double eta) {
  Shape s;
  const double L[3] = {1 - xi - eta, xi, eta};
  const double dLx[3] = {-1, 1, 0}, dLe[3] = {-1, 0, 1};
  if (n == 3) {
    for (int a = 0; a < 3; ++a) {
      s.N[a] = L[a];
      s.dxi[a] = dLx[a];
      s.deta[a] = dLe[a];
    }
    return s;
  }
  for (int a = 0; a < 3; ++a) {
    s.N[a] = L[a] * (2 * L[a] - 1);
    s.dxi[a] = (4 * L[a] - 1) * dLx[a];
    s.deta[a] = (4 * L[a] - 1) * dLe[a];
    const int b = (a + 1) % 3;  // edge node 3 + a sits on edge (a, b)
    s.N[3 + a] = 4 * L[a] * L[b];
    s.dxi[3 + a] = 4 * (dLx[a] * L[b] + L[a] * dLx[b]);
    s.deta[3 + a] = 4 * (dLe[a] * L[b] + L[a] * dLe[b]);
  }
  return s;
}

/// ∫ x·(x_ξ × x_η) dξ dη over the reference triangle (= ∫ x·n da) for node positions P
/// (3 or 6), and in g its gradient with respect to each position:
/// d[x·(x_ξ × x_η)] = dx·(x_ξ × x_η) + dx_ξ·(x_η × x) + dx_η·(x × x_ξ).
double flux_of_position(const std::vector<Vec3>& P, std::vector<Vec3>& g) {
  const int n = static_cast<int>(P.size());
  g.assign(n, Vec3::Zero());
  double value = 0.0;
  for (const auto& q : kPoints) {
    const double w = 0.5 * q[2];
    const Shape s = shape(n, q[0], q[1]);
    Vec3 x = Vec3::Zero(), x_xi = Vec3::Zero(), x_eta = Vec3::Zero();
    for (int a = 0; a < n; ++a) {
      x += s.N[a] * P[a];
      x_xi += s.dxi[a] * P[a];
      x_eta += s.deta[a] * P[a];
    }
    const Vec3 normal = x_xi.cross(x_eta), d_xi = x_eta.cross(x), d_eta = x.cross(x_xi);
    value += w * x.dot(normal);
    for (int a = 0; a < n; ++a) g[a] += w * (s.N[a] * normal + s.dxi[a] * d_xi + s.deta[a] * d_eta);
  }
  return value;
}

[[noreturn]] void no_such_face(const TetMesh& m, const std::string& face) {
  std::vector<std::string> known;
  for (const auto& [name, _] : m.faces) known.push_back(name);
  throw InputError(fmt::format("cavity volume: face '{}': expected {}", face,
                               known_names("a named face of the mesh", face, known)));
}

}  // namespace

CavityVolume cavity_volume(const TetMesh& m, const std::string& face, const Eigen::VectorXd& u) {
  const auto it = m.faces.find(face);
  if (it == m.faces.end()) no_such_face(m, face);
  if (u.size() != 3 * static_cast<Eigen::Index>(m.num_nodes()))
    throw InputError(fmt::format("cavity volume of '{}': displacement vector of size {}, expected 3 x {} nodes = {}",
                                 face, u.size(), m.num_nodes(), 3 * m.num_nodes()));
  const auto& tris = it->second;
  const auto x = [&](int node) -> Vec3 { return m.nodes[node] + u.segment<3>(3 * node); };

  // S = (1/3) ∮ x·n da with normals into the cavity; V = -S.
  double S = 0.0;
  std::vector<Vec3> grad(m.num_nodes(), Vec3::Zero());
  std::vector<char> touched(m.num_nodes(), 0);
  std::vector<Vec3> P, g;
  for (const auto& tri : tris) {
    const auto nodes = m.face_nodes(tri);
    P.clear();
    for (int n : nodes) P.push_back(x(n));
    S += flux_of_position(P, g) / 3.0;
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      grad[nodes[a]] += g[a] / 3.0;
      touched[nodes[a]] = 1;
    }
  }

  // The boundary ring: edges of exactly one triangle, kept in the direction that triangle
  // runs them (the std::map makes the order, and so the sums, deterministic).
  std::map<std::pair<int, int>, std::pair<int, std::array<int, 2>>> edges;  // key -> (count, a->b)
  for (const auto& tri : tris)
    for (int a = 0; a < 3; ++a) {
      auto& e = edges[std::minmax(tri[a], tri[(a + 1) % 3])];
      ++e.first;
      e.second = {tri[a], tri[(a + 1) % 3]};
    }
  std::vector<std::array<int, 2>> ring;
  std::vector<int> ring_nodes;
  for (const auto& [key, e] : edges)
    if (e.first == 1) {
      ring.push_back(e.second);
      ring_nodes.push_back(key.first);
      ring_nodes.push_back(key.second);
      if (m.order() == 2) ring_nodes.push_back(m.edge_node(key.first, key.second));
    }
  std::sort(ring_nodes.begin(), ring_nodes.end());
  ring_nodes.erase(std::unique(ring_nodes.begin(), ring_nodes.end()), ring_nodes.end());

  if (!ring.empty()) {
    Vec3 c = Vec3::Zero();
    for (int n : ring_nodes) c += x(n);
    c /= static_cast<double>(ring_nodes.size());
    Vec3 grad_c = Vec3::Zero();
    for (const auto& [a, b] : ring) {
      // Cap triangle (b, a, c): runs the ring edge against the surface, so the closed
      // surface is consistently oriented.
      P = {x(b), x(a), c};
      if (m.order() == 2) P.insert(P.end(), {x(m.edge_node(a, b)), 0.5 * (x(a) + c), 0.5 * (c + x(b))});
      S += flux_of_position(P, g) / 3.0;
      grad[b] += g[0] / 3.0;
      grad[a] += g[1] / 3.0;
      grad_c += g[2] / 3.0;
      if (m.order() == 2) {
        grad[m.edge_node(a, b)] += g[3] / 3.0;
        grad[a] += g[4] / 6.0;
        grad_c += g[4] / 6.0 + g[5] / 6.0;
        grad[b] += g[5] / 6.0;
      }
    }
    // c is the mean of the ring nodes: each gets an equal share of ∂S/∂c.
    for (int n : ring_nodes) {
      grad[n] += grad_c / static_cast<double>(ring_nodes.size());
      touched[n] = 1;
    }
  }

  CavityVolume result;
  result.volume = -S;
  for (int n = 0; n < m.num_nodes(); ++n)
    if (touched[n])
      for (int i = 0; i < 3; ++i) result.dV_du.emplace_back(3 * n + i, -grad[n][i]);
  return result;
}

}  // namespace fe2
