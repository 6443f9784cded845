#include "common/mesh/lv_mesh.h"

#include "common/error.h"
#include "common/mesh/kuhn_split.h"

#include <cmath>
#include <string>

namespace fe2 {

namespace {

constexpr const char* kSource = "make_lv_mesh";

// A grid point (i, k, j): shell i (transmural, 0 = endo), azimuth index k (not wrapped:
// k = circumferential is the same point as k = 0), ring j from the apex (j = 0 apex).
using GridPoint = std::array<int, 3>;

void check(bool ok, const std::string& name, double value, const std::string& expected) {
  if (!ok) throw InputError(fmt::format("{}: {} = {}: expected {}", kSource, name, value, expected));
}

void check_params(const LvMeshParams& p) {
  check(std::isfinite(p.endo_short) && p.endo_short > 0, "endo_short", p.endo_short, "a semi-axis > 0");
  check(std::isfinite(p.endo_long) && p.endo_long > 0, "endo_long", p.endo_long, "a semi-axis > 0");
  check(std::isfinite(p.epi_short) && p.epi_short > p.endo_short, "epi_short", p.epi_short,
        fmt::format("a semi-axis > endo_short = {} (the epicardium encloses the endocardium)", p.endo_short));
  check(std::isfinite(p.epi_long) && p.epi_long > p.endo_long, "epi_long", p.epi_long,
        fmt::format("a semi-axis > endo_long = {} (the epicardium encloses the endocardium)", p.endo_long));
  check(std::isfinite(p.base_z) && p.base_z > -p.endo_long && p.base_z < p.endo_long, "base_z", p.base_z,
        fmt::format("a base plane cutting the endocardium, -{} < base_z < {}", p.endo_long, p.endo_long));
  check(p.circumferential >= 3 && p.circumferential <= 10000, "circumferential", p.circumferential,
        "an integer in [3, 10000]");
  check(p.longitudinal >= 1 && p.longitudinal <= 10000, "longitudinal", p.longitudinal, "an integer in [1, 10000]");
  check(p.transmural >= 1 && p.transmural <= 10000, "transmural", p.transmural, "an integer in [1, 10000]");
  check(6.0 * p.circumferential * p.longitudinal * p.transmural < 1e9, "circumferential*longitudinal*transmural",
        1.0 * p.circumferential * p.longitudinal * p.transmural, "fewer than 1.7e8 cells");
  check(p.order == 1 || p.order == 2, "order", p.order, "1 (4-node) or 2 (10-node tetrahedra)");
}

// The wall in parameters: shell t ∈ [0, 1], fraction s ∈ [0, 1] of the way from the apex
// to the base along the meridian, azimuth φ.
class WallMap {
 public:
  explicit WallMap(const LvMeshParams& p) : p_(p) {}

  Vec3 operator()(double t, double s, double phi) const {
    const double a = p_.endo_short + t * (p_.epi_short - p_.endo_short);
    const double c = p_.endo_long + t * (p_.epi_long - p_.endo_long);
    // Polar angle from the apex (-z) to where this shell meets the base plane.
    const double theta_base = std::acos(-p_.base_z / c);
    const double theta = s * theta_base;
    // On the base (s = 1) z is the plane exactly, so the base face is flat to the last bit.
    const double z = s == 1.0 ? p_.base_z : -c * std::cos(theta);
    const double r = a * std::sin(theta);
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  LvMeshParams p_;
};

}  // namespace

TetMesh make_lv_mesh(const LvMeshParams& p) {
  check_params(p);
  const int nc = p.circumferential, nl = p.longitudinal, nt = p.transmural;
  const WallMap map(p);

  // Nodes: the apex of each shell first (i), then rings j = 1..nl, azimuth k, shell i.
  const auto node_id = [&](const GridPoint& g) {
    const int i = g[0], k = g[1] % nc, j = g[2];
    return j == 0 ? i : (nt + 1) + i + (nt + 1) * (k + nc * (j - 1));
  };
  const auto param = [&](const GridPoint& g) {
    return std::array<double, 3>{double(g[0]) / nt, double(g[2]) / nl, 2.0 * M_PI * g[1] / nc};
  };

  TetMesh m;
  m.nodes.resize(static_cast<std::size_t>(nt + 1) * (1 + static_cast<std::size_t>(nc) * nl));
  for (int j = 0; j <= nl; ++j)
    for (int k = 0; k < (j == 0 ? 1 : nc); ++k)
      for (int i = 0; i <= nt; ++i) {
        const GridPoint g{i, k, j};
        const auto q = param(g);
        m.nodes[node_id(g)] = map(q[0], q[1], q[2]);
      }

  // Tets with the grid points of their corners (needed to place quadratic edge nodes).
  std::vector<std::array<GridPoint, 4>> tet_grid;
  // Kuhn split in the grid axes (t, φ, θ): a right-handed frame (outward,
  // counter-clockwise, toward the base), so the tets are positively oriented in space too.
  const auto kuhn = kuhn_tets();
  for (int j = 0; j < nl; ++j)
    for (int k = 0; k < nc; ++k)
      for (int i = 0; i < nt; ++i)
        for (const auto& corners : kuhn) {
          std::array<GridPoint, 4> g{};
          std::array<int, 4> t{};
          for (int a = 0; a < 4; ++a) {
            g[a] = {i + corners[a][0], k + corners[a][1], j + corners[a][2]};
            t[a] = node_id(g[a]);
          }
          // In an apex cell two corners of a tet may be the same apex node: a flat tet.
          bool flat = false;
          for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) flat = flat || t[a] == t[b];
          if (flat) continue;
          m.tets.push_back(t);
          tet_grid.push_back(g);
          // A tet face with its three corners on shell 0, shell nt or ring nl is a boundary face.
          for (int opp = 0; opp < 4; ++opp) {
            std::array<int, 3> tri{};
            std::array<GridPoint, 3> gf{};
            for (int a = 0, f = 0; a < 4; ++a)
              if (a != opp) {
                gf[f] = g[a];
                tri[f++] = t[a];
              }
            const auto all = [&](int axis, int value) {
              return gf[0][axis] == value && gf[1][axis] == value && gf[2][axis] == value;
            };
            if (all(0, 0)) m.faces["endo"].push_back(tri);
            if (all(0, nt)) m.faces["epi"].push_back(tri);
            if (all(2, nl)) m.faces["base"].push_back(tri);
          }
        }
  m.region.assign(m.tets.size(), 1);
  orient_named_surfaces(m, kSource);
  m.node_sets["apex_endo"] = {node_id({0, 0, 0})};
  m.node_sets["apex_epi"] = {node_id({nt, 0, 0})};

  if (p.order == 2) {
    for (std::size_t e = 0; e < tet_grid.size(); ++e)
      for (const auto& [a, b] : kTetEdges) {
        const auto key = std::minmax(m.tets[e][a], m.tets[e][b]);
        if (m.edge_nodes.count(key)) continue;
        auto qa = param(tet_grid[e][a]), qb = param(tet_grid[e][b]);
        // The apex has no azimuth of its own: an edge from it follows the other end's meridian.
        if (tet_grid[e][a][2] == 0) qa[2] = qb[2];
        if (tet_grid[e][b][2] == 0) qb[2] = qa[2];
        m.edge_nodes[key] = m.num_nodes();
        m.nodes.push_back(map(0.5 * (qa[0] + qb[0]), 0.5 * (qa[1] + qb[1]), 0.5 * (qa[2] + qb[2])));
      }
  }
  // Derives the face node sets (with their edge nodes) and checks every tet is positive.
  validate_mesh(m, kSource);
  return m;
}

}  // namespace fe2
