#include "common/mesh/lv_mesh.h"

#include "common/error.h"
#include "common/mesh/kuhn_split.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fe2 {

namespace {

constexpr const char* kSource = "make_lv_mesh";

// A grid point (i, k, j): shell i (transmural, 0 = endo; negative: the cavity's shells,
// -cavity_layers = the long axis), azimuth index k (not wrapped: k = circumferential is
// the same point as k = 0), ring j from the apex (j = 0 apex).
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
  check(p.cavity_layers >= 0 && p.cavity_layers <= 10000, "cavity_layers", p.cavity_layers,
        "an integer in [0, 10000] (0: no cavity)");
  const double cells = 1.0 * p.circumferential * p.longitudinal * (p.transmural + p.cavity_layers);
  check(6.0 * cells < 1e9, "circumferential*longitudinal*(transmural+cavity_layers)", cells, "fewer than 1.7e8 cells");
  check(p.order == 1 || p.order == 2, "order", p.order, "1 (4-node) or 2 (10-node tetrahedra)");
  if (p.rings.empty()) return;
  if (p.cavity_layers == 0)
    throw InputError(fmt::format("{}: ring '{}' given without a cavity: expected cavity_layers >= 1 (rings are "
                                 "discs of the cavity's base cap)",
                                 kSource, p.rings.front().name));
  // The cavity's base cap is the disc of the endocardium in the base plane.
  const double cap_radius = p.endo_short * std::sqrt(1.0 - p.base_z * p.base_z / (p.endo_long * p.endo_long));
  for (std::size_t r = 0; r < p.rings.size(); ++r) {
    const LvBaseRing& ring = p.rings[r];
    for (const char* taken : {"endo", "epi", "base", "base_cap", "apex_endo", "apex_epi"})
      if (ring.name == taken)
        throw InputError(fmt::format("{}: ring name '{}' is the generator's own set, expected another name", kSource,
                                     ring.name));
    const std::string what = fmt::format("ring '{}'", ring.name);
    check(std::isfinite(ring.radius) && ring.radius > 0, what + " radius", ring.radius, "a radius > 0");
    const double reach = std::hypot(ring.x, ring.y) + ring.radius;
    check(std::isfinite(reach) && reach <= cap_radius, what + " centre distance + radius", reach,
          fmt::format("a disc inside the cavity's base cap (radius {:.6g})", cap_radius));
    for (std::size_t q = 0; q < r; ++q) {
      const LvBaseRing& other = p.rings[q];
      if (other.name == ring.name)
        throw InputError(fmt::format("{}: ring '{}' given twice, expected each name once", kSource, ring.name));
      const double gap = std::hypot(ring.x - other.x, ring.y - other.y) - ring.radius - other.radius;
      check(gap >= 0, fmt::format("{} and ring '{}': gap", what, other.name), gap, "discs that do not overlap (>= 0)");
    }
  }
}

// The wall in parameters: shell t ∈ [0, 1], fraction s ∈ [0, 1] of the way from the apex
// to the base along the meridian, azimuth φ. The cavity continues it to t ∈ [-1, 0):
// shells of semi-axes ((1 + t) r_s, r_l + t d) down to the long axis at t = -1, each with
// an apex of its own on the axis, d above the last. Shells through one apex would meet the
// endocardium tangentially there: the blood's apex elements would be slivers that the
// beating wall's apex folds (docs/fluid.md). d is the shells' spacing at the equator
// (r_s), less where the base plane is near: the axis keeps half its length below it.
class WallMap {
 public:
  explicit WallMap(const LvMeshParams& p)
      : p_(p), apex_rise_(std::min(p.endo_short, 0.5 * (p.endo_long - std::abs(p.base_z)))) {}

  Vec3 operator()(double t, double s, double phi) const {
    const double a = t < 0 ? (1.0 + t) * p_.endo_short : p_.endo_short + t * (p_.epi_short - p_.endo_short);
    const double c = t < 0 ? p_.endo_long + t * apex_rise_ : p_.endo_long + t * (p_.epi_long - p_.endo_long);
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
  double apex_rise_;  ///< d: how far the axis's end lies above the endocardial apex
};

/// The base-cap triangles whose centroid lies in a ring's disc become that ring's face;
/// the rest stay `base_cap`.
void split_base_cap(TetMesh& m, const LvMeshParams& p, std::vector<std::array<int, 3>> cap) {
  auto& rest = m.faces["base_cap"];
  for (const auto& tri : cap) {
    const Vec3 c = (m.nodes[tri[0]] + m.nodes[tri[1]] + m.nodes[tri[2]]) / 3.0;
    const LvBaseRing* in = nullptr;
    for (const LvBaseRing& r : p.rings)
      if (std::hypot(c.x() - r.x, c.y() - r.y) < r.radius) in = &r;
    (in ? m.faces[in->name] : rest).push_back(tri);
  }
  for (const LvBaseRing& r : p.rings)
    if (!m.faces.count(r.name))
      throw InputError(fmt::format("{}: ring '{}' (radius {}) holds no base-cap triangle: expected a disc covering "
                                   "at least one (more divisions, or a larger radius)",
                                   kSource, r.name, r.radius));
  if (rest.empty()) m.faces.erase("base_cap");
}

}  // namespace

TetMesh make_lv_mesh(const LvMeshParams& p) {
  check_params(p);
  const int nc = p.circumferential, nl = p.longitudinal, nt = p.transmural, nb = p.cavity_layers;
  const WallMap map(p);

  // Nodes: the apex of each shell first (i), then rings j = 1..nl, azimuth k, shell i;
  // then the cavity's: the axis point of each ring j, then its shells -nb < i < 0, then
  // the apices of its shells.
  const int wall_nodes = (nt + 1) * (1 + nc * nl);
  const int cavity_apices = wall_nodes + nl * (1 + (nb - 1) * nc);
  const auto node_id = [&](const GridPoint& g) {
    const int i = g[0], k = g[1] % nc, j = g[2];
    if (i < 0) {
      if (j == 0) return cavity_apices + (-i - 1);
      if (i == -nb) return wall_nodes + (j - 1);
      return wall_nodes + nl + (-i - 1) + (nb - 1) * (k + nc * (j - 1));
    }
    return j == 0 ? i : (nt + 1) + i + (nt + 1) * (k + nc * (j - 1));
  };
  const auto param = [&](const GridPoint& g) {
    const double t = g[0] < 0 ? double(g[0]) / nb : double(g[0]) / nt;
    return std::array<double, 3>{t, double(g[2]) / nl, 2.0 * M_PI * g[1] / nc};
  };

  TetMesh m;
  m.nodes.resize(static_cast<std::size_t>(wall_nodes) +
                 (nb > 0 ? nl * (1 + static_cast<std::size_t>(nb - 1) * nc) + nb : 0));
  for (int j = 0; j <= nl; ++j)
    for (int k = 0; k < (j == 0 ? 1 : nc); ++k)
      for (int i = -nb; i <= nt; ++i) {
        if (i < 0 && i == -nb && k > 0) continue;  // one node on the axis per ring
        const GridPoint g{i, k, j};
        const auto q = param(g);
        m.nodes[node_id(g)] = map(q[0], q[1], q[2]);
      }

  // Tets with the grid points of their corners (needed to place quadratic edge nodes).
  std::vector<std::array<GridPoint, 4>> tet_grid;
  std::vector<std::array<int, 3>> cap;  // the cavity's base-plane triangles
  // Kuhn split in the grid axes (t, φ, θ): a right-handed frame (outward,
  // counter-clockwise, toward the base), so the tets are positively oriented in space too.
  const auto kuhn = kuhn_tets();
  for (int j = 0; j < nl; ++j)
    for (int k = 0; k < nc; ++k)
      for (int i = -nb; i < nt; ++i)
        for (const auto& corners : kuhn) {
          std::array<GridPoint, 4> g{};
          std::array<int, 4> t{};
          for (int a = 0; a < 4; ++a) {
            g[a] = {i + corners[a][0], k + corners[a][1], j + corners[a][2]};
            t[a] = node_id(g[a]);
          }
          // Where grid points collapse (the apex, the axis) a tet may have two corners
          // on the same node: a flat tet.
          bool flat = false;
          for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) flat = flat || t[a] == t[b];
          if (flat) continue;
          m.tets.push_back(t);
          m.region.push_back(i < 0 ? 2 : 1);
          tet_grid.push_back(g);
          // A tet face with its three corners on shell 0, shell nt or ring nl is a boundary face
          // (shell 0 only seen from the wall: with a cavity it is the interface).
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
            if (i >= 0 && all(0, 0)) m.faces["endo"].push_back(tri);
            if (all(0, nt)) m.faces["epi"].push_back(tri);
            if (all(2, nl)) (i >= 0 ? m.faces["base"] : cap).push_back(tri);
          }
        }
  if (nb > 0) {
    m.region_names = {{1, "myocardium"}, {2, "blood"}};
    split_base_cap(m, p, std::move(cap));
  }
  orient_named_surfaces(m, kSource);
  m.node_sets["apex_endo"] = {node_id({0, 0, 0})};
  m.node_sets["apex_epi"] = {node_id({nt, 0, 0})};

  if (p.order == 2) {
    // A collapsed grid point has no azimuth of its own (a shell's apex, the axis): an edge
    // from it follows the other end's, so that it is the same curve whichever tet meets
    // it first (and straight along the axis).
    const auto edge_end = [&](const GridPoint& g, const GridPoint& other) {
      auto q = param(g);
      if (g[2] == 0 || (nb > 0 && g[0] == -nb)) q[2] = param(other)[2];
      return q;
    };
    // Inside the cavity the edges are straight: its grid map (τ r_s sin θ, ...) is a
    // product that collapses at the axis and at the shells' apices, and following it would
    // only twist the elements. Edges on the endocardium follow it, as the wall's do.
    const auto inside_cavity = [](const GridPoint& g) { return g[0] < 0; };
    for (std::size_t e = 0; e < tet_grid.size(); ++e)
      for (const auto& [a, b] : kTetEdges) {
        const auto key = std::minmax(m.tets[e][a], m.tets[e][b]);
        if (m.edge_nodes.count(key)) continue;
        const GridPoint &ga = tet_grid[e][a], &gb = tet_grid[e][b];
        const auto qa = edge_end(ga, gb), qb = edge_end(gb, ga);
        m.edge_nodes[key] = m.num_nodes();
        m.nodes.push_back(inside_cavity(ga) || inside_cavity(gb) ? Vec3(0.5 * (m.nodes[key.first] + m.nodes[key.second]))
                                           : map(0.5 * (qa[0] + qb[0]), 0.5 * (qa[1] + qb[1]),
                                                 0.5 * (qa[2] + qb[2])));
      }
  }
  // Derives the face node sets (with their edge nodes) and checks every tet is positive.
  validate_mesh(m, kSource);
  return m;
}

}  // namespace fe2
