#include "common/io/vtu_writer.h"
#include "tools/commands.h"
#include "tools/memory_limit.h"
#include "tools/unit_spec.h"
#include "worker/unit_equilibrium.h"

#include <spdlog/spdlog.h>

#include <cmath>

namespace fe2::cli {

int unit(const UnitOptions& o) {
  UnitSpec spec = read_unit_spec(read_json_file(o.spec), o.spec, nullptr, false);
  check_unit_memory(*spec.plan, 1, memory_limit(""));  // before anything big is allocated
  spec.model = spec.plan->build();
  MicroUnit unit(spec.model);
  json results = json::array();
  UnitEquilibrium last;
  for (size_t s = 0; s < spec.path.size(); ++s) {
    last = equilibrate(unit, spec.path[s], spec.rtol, spec.max_iterations, static_cast<int>(s));
    results.push_back({{"Zbar", std::vector<double>(spec.path[s].data(), spec.path[s].data() + 9)},
                       {"P_bar", std::vector<double>(last.P_bar.data(), last.P_bar.data() + 9)},
                       {"A_hom", std::vector<double>(last.A_hom.data(), last.A_hom.data() + 81)},
                       {"newton_iterations", last.newton_iterations},
                       {"gmres_iterations", last.gmres_iterations},
                       {"residuals", last.residuals}});
  }
  json out = results.back();
  out["dofs"] = spec.model->num_dofs();
  out["elements"] = spec.model->num_elements();
  out["convention"] = "column-major 9-vectors (11,21,31,12,22,32,13,23,33); A_hom[r + 9c] = dP_r/dZ_c";
  if (spec.path.size() > 1) out["path"] = results;
  if (!o.vtu.empty()) {
    const HexMesh& mesh = spec.model->mesh();
    std::vector<Vec3> w(mesh.num_nodes(), Vec3::Zero());
    for (int a = 0; a < mesh.num_nodes(); ++a)
      for (int i = 0; i < 3; ++i) {
        const int d = spec.model->dofs().dof(a, i);
        w[a][i] = d >= 0 ? unit.w()[d] : 0.0;
      }
    VtuFields point, cell;
    point.add_vector("w", w);
    std::vector<double> region(mesh.region.begin(), mesh.region.end());
    cell.add_scalar("region", region);
    write_vtu(o.vtu, mesh, point, cell);
  }
  fmt::print("{}\n", out.dump(2));
  return 0;
}

}  // namespace fe2::cli
