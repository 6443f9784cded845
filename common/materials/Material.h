#pragma once
// A hyperelastic material in its own frame (axis 1 = fibre, 2 = sheet, 3 = normal).
// Three verbs, as MFEM's HyperelasticModel: energy W(Z), stress Π = ∂W/∂Z (first
// Piola–Kirchhoff), tangent 𝔸 = ∂Π/∂Z (9x9, row = Π component, column = Z component,
// both column-major 9-vectors; DESIGN §1). Z = ∂u/∂X, F = I + Z.
//
// Implementations throw fe2::NumericalError when det F <= 0 (an inverted point), so a
// Newton driver can cut its step back; they never return NaN silently.
#include "common/materials/MaterialPointContext.h"
#include "common/tensor9.h"

#include <algorithm>
#include <memory>
#include <span>
#include <string>

namespace fe2 {

class Material {
 public:
  virtual ~Material() = default;

  /// Short model name as written in specs, e.g. "neo_hookean".
  virtual std::string name() const = 0;

  /// One line for the log: the model and what it adds (cell model, parameter set, ...).
  virtual std::string description() const { return name(); }

  /// Strain energy per unit reference volume, W(Z).
  virtual double energy(const Vec9& Z) const = 0;

  /// Π(Z) and 𝔸(Z) together (the hot path: one call per micro Gauss point).
  virtual void stress_and_tangent(const Vec9& Z, Vec9& Pi, Mat9& A) const = 0;

  /// Π(Z) alone; default evaluates the pair.
  virtual Vec9 stress(const Vec9& Z) const {
    Vec9 Pi;
    Mat9 A;
    stress_and_tangent(Z, Pi, A);
    return Pi;
  }

  /// 𝔸(Z) alone; default evaluates the pair.
  Mat9 tangent(const Vec9& Z) const {
    Vec9 Pi;
    Mat9 A;
    stress_and_tangent(Z, Pi, A);
    return A;
  }

  /// A representative small-strain stiffness (Pa), used to scale tolerances.
  virtual double stiffness_scale() const = 0;

  /// Whether 𝔸 has major symmetry (true for every hyperelastic law).
  virtual bool major_symmetric() const { return true; }

  // --- Material points with a context (MaterialPointContext.h) ---

  /// Doubles of history (internal variables) the law keeps per material point; 0 for a
  /// law that is a pure function of Z.
  virtual int history_size() const { return 0; }

  /// Whether the law reads its context (t, Δt, Ż, history). Point models compute no
  /// context for laws that do not, so stateless laws cost nothing extra.
  virtual bool uses_context() const { return history_size() > 0; }

  /// Π and its two tangents at a point with its context: reads history.committed,
  /// writes history.current (history_size() doubles each).
  ///   A       = ∂Π/∂Z at fixed Ż   (through the step's history update)
  ///   A_rate  = ∂Π/∂Ż at fixed Z   (zero unless rate_dependent())
  /// The point model builds its step tangent from its own rate rule: with
  /// Ż = c (Z − Z_n) + …, 𝔸 = A + c·A_rate (c = 1/Δt for backward Euler, γ/(βΔt) under
  /// Newmark). Default: the stateless pair.
  virtual void stress_and_tangent_at(const Vec9& Z, const MaterialPointContext& context,
                                     PointHistory history, Vec9& Pi, Mat9& A,
                                     Mat9& A_rate) const {
    stress_and_tangent(Z, Pi, A);
    A_rate.setZero();
  }

  /// Where the point's active fibre tension T_a sits in its history (for output), or −1.
  virtual int active_tension_slot() const { return -1; }

  /// Whether Π depends on Ż (A_rate may be nonzero).
  virtual bool rate_dependent() const { return false; }

  /// The history of a point that has seen nothing yet (a resting cell): history_size()
  /// doubles. Default: zeros.
  virtual void initial_history(std::span<double> history) const {
    std::fill(history.begin(), history.end(), 0.0);
  }

  /// Serialization of parameters is by spec (materials are rebuilt from JSON).
};

using MaterialPtr = std::shared_ptr<const Material>;

}  // namespace fe2
