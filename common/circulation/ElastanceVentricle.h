#pragma once
// A ventricle as a time-varying elastance, standing in for the wall model so a
// circulation runs alone (`fe2heart circulation`): p = E(t)(V − V0), E(t) as the atria's
// (TimeVaryingElastance.h) with ventricular timing.
//
// couple_step() is the strong coupling the macro model does with its wall: the cavity
// pressures p are the unknowns of
//   F_c(p) = p_c − E_c(t_{n+1}) (V_c,n + Δt Q_net,c(p) − V0_c) = 0,
// solved by Newton with J = I − diag(E) Δt ∂Q_net/∂p (the circulation's exact Jacobian).
// The new volumes are then V_c,n + Δt Q_net,c(p), so a closed loop conserves blood.
#include "common/circulation/Circulation.h"
#include "common/circulation/TimeVaryingElastance.h"

#include <span>
#include <vector>

namespace fe2 {

class ElastanceVentricle {
 public:
  ElastanceVentricle(const ElastanceParameters& p, double period) : e_(p, period) {}
  double pressure(double t, double V) const { return e_.pressure(t, V); }
  double elastance(double t) const { return e_.elastance(t); }
  double initial_volume() const { return e_.parameters().V_init; }
  double V0() const { return e_.parameters().V0; }
  const TimeVaryingElastance& law() const { return e_; }

 private:
  TimeVaryingElastance e_;
};

/// One coupled step: `p` holds the initial guess (e.g. the last pressures) and returns
/// the converged cavity pressures; `V` holds V_n and returns V_{n+1}; the circulation
/// state goes from `committed` to `current`. Returns the flows at the solution; throws
/// NumericalError if the Newton on p fails.
CavityFlows couple_step(const Circulation& circulation,
                        const std::vector<ElastanceVentricle>& ventricles, double t_new, double dt,
                        std::span<const double> committed, std::span<double> current,
                        std::vector<double>& p, std::vector<double>& V, int* iterations = nullptr);

}  // namespace fe2
