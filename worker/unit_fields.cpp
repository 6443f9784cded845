#include "worker/unit_fields.h"

#include "worker/micro_kernel.h"

namespace fe2 {

proto::UnitFields micro_fields(const MicroUnit& micro, int unit, int step) {
  const MicroModel& m = micro.model();
  const HexMesh& mesh = m.mesh();
  const int ne = m.num_elements();
  proto::UnitFields f;
  f.unit = unit;
  f.step = step;
  f.Zbar = micro.Zbar();

  // Re-assemble at the unit's state with a scratch history (the unit keeps its own):
  // each element's share of P̄, and P̄ itself.
  MicroUnit::System sys;
  sys.K = m.zero_matrix();
  std::vector<Vec9> share;
  micro.assemble_at(micro.w(), f.Zbar, sys, nullptr, &share);
  f.P_bar = sys.Pbar;

  // w per node: a periodic image carries its master's value, the pinned node 0.
  f.w.assign(3 * static_cast<size_t>(mesh.num_nodes()), 0.0);
  for (int a = 0; a < mesh.num_nodes(); ++a)
    for (int i = 0; i < 3; ++i) {
      const int d = m.dofs().dof(a, i);
      f.w[3 * static_cast<size_t>(a) + i] = d >= 0 ? micro.w()[d] : 0.0;
    }

  f.P.assign(9 * static_cast<size_t>(ne), 0.0);
  f.det_F.assign(ne, 0.0);
  f.active_tension.assign(ne, 0.0);
  const std::vector<double>& history = micro.history();
  const double inv_volume = m.inv_volume();
  Eigen::Matrix<double, 3, 8> w_e;
  for (int e = 0; e < ne; ++e) {
    const HexGeometry& geo = m.geometry(e);
    const auto& eq = m.element_equations(e);
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) {
        const int g = eq[hex_local(i, a)];
        w_e(i, a) = g >= 0 ? micro.w()[g] : 0.0;
      }
    double volume = 0.0, detF = 0.0;
    for (int q = 0; q < 8; ++q) {
      // Z = Z̄ + B̃w at the Gauss point, as the kernel forms it.
      const Mat3 F = Mat3::Identity() + as_mat3(f.Zbar) + w_e * geo.grad[q].transpose();
      volume += geo.weight[q];
      detF += geo.weight[q] * F.determinant();
    }
    // The share is Σ_q ω_q Π_q with ω_q = weight_q / |Y|: divided by |e| / |Y| it is the
    // element's volume mean of Π.
    const Vec9 P_e = share[e] / (volume * inv_volume);
    std::copy(P_e.data(), P_e.data() + 9, &f.P[9 * static_cast<size_t>(e)]);
    f.det_F[e] = detF / volume;
    const Material& law = m.material_of(e);
    const int slot = law.active_tension_slot();
    if (slot < 0) continue;
    f.active = true;
    const size_t h = static_cast<size_t>(law.history_size()), at = m.history_offset(e);
    double Ta = 0.0;
    for (int q = 0; q < 8; ++q) Ta += geo.weight[q] * history[at + q * h + static_cast<size_t>(slot)];
    f.active_tension[e] = Ta / volume;
  }
  return f;
}

}  // namespace fe2
