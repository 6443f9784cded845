#include "worker/unit_equilibrium.h"

namespace fe2 {

UnitEquilibrium equilibrate(MicroUnit& unit, const Vec9& Zbar, double rtol, int max_iterations,
                            int step) {
  proto::JobInput in;
  in.step = step;
  in.Zbar = Zbar;
  return equilibrate(unit, in, rtol, max_iterations);
}

UnitEquilibrium equilibrate(MicroUnit& unit, const proto::JobInput& job, double rtol,
                            int max_iterations) {
  UnitEquilibrium eq;
  proto::JobInput in = job;
  in.unit = 0;
  in.force_refresh = 0;
  for (int it = 1; it <= max_iterations; ++it) {
    in.iteration = it;
    in.apply_update = it > 1;
    const proto::JobOutput out = unit.iterate(in);
    eq.gmres_iterations += out.gmres_iterations;
    eq.residuals.push_back(out.r_norm / out.r_ref);
    if (proto::relative_residual(out) <= rtol) {  // or at its round-off floor
      eq.newton_iterations = it;
      // Same state, fresh factor and modes: the exact homogenized tangent.
      in.apply_update = 0;
      in.force_refresh = 1;
      in.iteration = it + 1;
      const proto::JobOutput fin = unit.iterate(in);
      eq.P_bar = fin.P_bar;
      eq.A_hom = fin.A_hom;
      unit.commit_step();
      return eq;
    }
  }
  throw NumericalError(fmt::format(
      "micro unit did not equilibrate in {} iterations (last ‖r‖/r_ref = {:.3e}, target {:.1e})",
      max_iterations, eq.residuals.back(), rtol));
}

}  // namespace fe2
