#pragma once
// A cell model: calcium → cross-bridges → the active fibre tension T_a at one material
// point (a macro-law point, or a Gauss point of a unit's cell region). The model is a
// pure function of its committed state and the step; the point that owns the state
// commits, rolls back and serializes it (MaterialPointContext.h).
//
// Units: time in seconds, tension in Pa, calcium in µM. The step takes the fibre
// stretch λ = |F f₀| at t_{n+1} and its rate λ̇, held constant over the step, so that
// λ(s) = λ − (t_{n+1} − s) λ̇ on [t_n, t_{n+1}].
//
// `advance` returns T_a(t_{n+1}) and its derivatives with respect to λ and λ̇ *through
// the whole step update* (the state at t_{n+1} depends on both): the consistent tangent
// of the active stress needs exactly these.
#include <memory>
#include <span>
#include <string>

namespace fe2 {

/// One step [t_n, t_{n+1}] as a cell model sees it.
struct CellStep {
  double time = 0.0;             ///< t_{n+1} (s)
  double dt = 0.0;               ///< Δt (s); 0: no step, T_a from the committed state at λ
  double activation_time = 0.0;  ///< the point's activation time t_act (s)
  double lambda = 1.0;           ///< fibre stretch at t_{n+1}
  double lambda_dot = 0.0;       ///< fibre stretch rate (1/s), constant over the step
};

/// T_a at t_{n+1} and its sensitivities (Pa, Pa, Pa·s).
struct ActiveTension {
  double Ta = 0.0;
  double dTa_dlambda = 0.0;
  double dTa_dlambda_dot = 0.0;
};

class CellModel {
 public:
  virtual ~CellModel() = default;

  /// Spec name, e.g. "land2017".
  virtual std::string name() const = 0;

  /// One line naming the model, its parameter set and values that matter (logged).
  virtual std::string description() const = 0;

  /// Doubles of state per material point (0 for a prescribed tension).
  virtual int state_size() const = 0;

  /// The state of a resting cell (diastolic calcium, λ = 1), state_size() doubles.
  virtual void rest_state(std::span<double> state) const = 0;

  /// Advances `committed` (read only) over the step into `current` (both state_size()
  /// doubles) and returns T_a(t_{n+1}) with its sensitivities. With step.dt == 0 the
  /// state is copied and T_a evaluated from it at step.lambda. Deterministic: the same
  /// inputs give the same bits.
  virtual ActiveTension advance(const CellStep& step, std::span<const double> committed,
                                std::span<double> current) const = 0;

  /// Whether T_a depends on λ̇ (the tangent is then unsymmetric and the unit takes the
  /// LU path).
  virtual bool rate_dependent() const = 0;
};

using CellModelPtr = std::shared_ptr<const CellModel>;

}  // namespace fe2
