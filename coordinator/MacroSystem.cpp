#include "coordinator/MacroSystem.h"

namespace fe2 {

MacroSystem::MacroSystem(const RunSpec& spec, const std::vector<int>& owned_tets, int part, int parts)
    : spec_(spec), num_nodes_(spec.mesh.num_nodes()) {
  const TetMesh& m = spec.mesh;
  // Prescribed DOFs; a later condition on the same DOF overrides an earlier one.
  std::vector<int> source(3 * num_nodes_, -1);
  for (size_t d = 0; d < spec.dirichlet.size(); ++d)
    for (int node : m.node_sets.at(spec.dirichlet[d].set))
      for (int i = 0; i < 3; ++i)
        if (spec.dirichlet[d].fixed[i]) source[3 * node + i] = static_cast<int>(d);
  eq_.assign(3 * num_nodes_, -1);
  for (int dof = 0; dof < 3 * num_nodes_; ++dof) {
    if (source[dof] >= 0) {
      prescribed_.push_back(dof);
      prescribed_source_.emplace_back(source[dof], dof % 3);
    } else {
      eq_[dof] = num_free_++;
    }
  }
  // Pressure triangles are dealt out to the coordinators in turn (exclusively).
  int k = 0;
  for (size_t p = 0; p < spec.pressure.size(); ++p)
    for (const auto& tri : m.faces.at(spec.pressure[p].surface))
      if (k++ % parts == part) triangles_.push_back({tri, static_cast<int>(p)});

  auto add_block = [&](const int* nodes, int nn, std::vector<int>& map) {
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < 3; ++i)
        for (int b = 0; b < nn; ++b)
          for (int k = 0; k < 3; ++k) {
            const int r = eq_[3 * nodes[a] + i], c = eq_[3 * nodes[b] + k];
            if (r < 0 || c < 0) {
              map.push_back(-1);
              continue;
            }
            map.push_back(static_cast<int>(rows_.size()));
            rows_.push_back(r);
            cols_.push_back(c);
          }
  };
  for (int e : owned_tets) add_block(m.tets[e].data(), 4, tet_map_);
  for (const auto& t : triangles_) add_block(t.nodes.data(), 3, tri_map_);
}

double MacroSystem::prescribed_value(size_t k, double t) const {
  const auto [d, i] = prescribed_source_[k];
  const DirichletSpec& ds = spec_.dirichlet[d];
  return ds.value[i] * ramp_factor(ds.ramp, t, spec_.t_end);
}

void MacroSystem::add_tet(int k, const Eigen::Matrix<double, 12, 12>& Ke,
                          std::vector<double>& values) const {
  const int* map = &tet_map_[static_cast<size_t>(k) * 144];
  for (int l = 0; l < 12; ++l)
    for (int c = 0; c < 12; ++c)
      if (map[12 * l + c] >= 0) values[map[12 * l + c]] += Ke(l, c);
}

void MacroSystem::add_triangle(int k, const Eigen::Matrix<double, 9, 9>& Ke,
                               std::vector<double>& values) const {
  const int* map = &tri_map_[static_cast<size_t>(k) * 81];
  for (int l = 0; l < 9; ++l)
    for (int c = 0; c < 9; ++c)
      if (map[9 * l + c] >= 0) values[map[9 * l + c]] += Ke(l, c);
}

}  // namespace fe2
