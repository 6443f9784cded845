#include "coordinator/output/UnitOutput.h"

#include "common/error.h"

#include <filesystem>

namespace fe2 {

namespace fs = std::filesystem;

UnitOutput::UnitOutput(const std::string& dir, const RunSpec& spec) : dir_(dir + "/units") {
  if (spec.output_units.empty()) return;
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec || !fs::is_directory(dir_))
    throw InputError(fmt::format("--out '{}': cannot create the folder for output.units ({})",
                                 dir_, ec.message()));
  const std::vector<int> model = spec.model_of_points();
  for (int u : spec.output_units) {
    const PointModelSpec& m = spec.models.at(static_cast<size_t>(model.at(static_cast<size_t>(u))));
    FE2_CHECK(m.plan, "output.units: unit {} has no micro model (the reader checks this)", u);
    Series& s = units_[u];
    s.mesh = m.plan->file_mesh ? *m.plan->file_mesh : make_cell_mesh(*m.plan->layout);
    s.pvd = std::make_unique<PvdWriter>(pvd_path(u));
  }
}

std::string UnitOutput::pvd_path(int unit) const { return fmt::format("{}/unit_{}.pvd", dir_, unit); }

std::string UnitOutput::vtu_path(int unit, int step) const {
  return fmt::format("{}/unit_{}_{:05d}.vtu", dir_, unit, step);
}

std::pair<VtuFields, VtuFields> unit_vtu_fields(const HexMesh& mesh, const proto::UnitFields& f) {
  FE2_CHECK(f.nodes() == mesh.num_nodes() && f.cells() == mesh.num_hexes(),
            "fields of unit {}: {} nodes and {} cells, its mesh has {} and {}", f.unit, f.nodes(),
            f.cells(), mesh.num_nodes(), mesh.num_hexes());
  const Mat3 Z = as_mat3(f.Zbar);
  std::vector<Vec3> u(mesh.num_nodes()), w(mesh.num_nodes());
  for (int a = 0; a < mesh.num_nodes(); ++a) {
    w[a] = Eigen::Map<const Vec3>(&f.w[3 * static_cast<size_t>(a)]);
    u[a] = Z * mesh.nodes[a] + w[a];  // the full micro displacement
  }
  std::vector<Vec9> P(f.cells());
  for (int e = 0; e < f.cells(); ++e) P[e] = Eigen::Map<const Vec9>(&f.P[9 * static_cast<size_t>(e)]);
  VtuFields point, cell;
  point.add_vector("displacement", u);
  point.add_vector("fluctuation", w);
  cell.add_tensor("P", P);
  cell.add_scalar("det_F", f.det_F);
  if (f.active) cell.add_scalar("active_tension", f.active_tension);
  return {std::move(point), std::move(cell)};
}

void UnitOutput::write(const std::vector<proto::UnitFields>& fields, double time) {
  for (const proto::UnitFields& f : fields) {
    auto it = units_.find(f.unit);
    FE2_CHECK(it != units_.end(), "fields of unit {}, which output.units does not name", f.unit);
    const auto [point, cell] = unit_vtu_fields(it->second.mesh, f);
    const std::string path = vtu_path(f.unit, f.step);
    write_vtu(path, it->second.mesh, point, cell);
    it->second.pvd->add(time, path);
  }
}

void UnitOutput::resume(const std::vector<std::pair<int, double>>& output_steps) {
  for (auto& [unit, series] : units_)
    for (const auto& [step, time] : output_steps)
      if (fs::exists(vtu_path(unit, step))) series.pvd->add(time, vtu_path(unit, step));
}

}  // namespace fe2
