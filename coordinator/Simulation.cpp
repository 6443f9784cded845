#include "coordinator/Simulation.h"

#include "common/cpu_timer.h"
#include "common/mesh/point_locator.h"
#include "coordinator/follower_pressure.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace fe2 {

namespace {

using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;

/// Consistent mass of a linear tet: M_ab = ρ|e|/20 (1 + δ_ab) I₃.
Mat12 tet_mass(double rho, double volume) {
  Mat12 M = Mat12::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      M.block<3, 3>(3 * a, 3 * b) = (rho * volume / 20.0 * (a == b ? 2.0 : 1.0)) * Mat3::Identity();
  return M;
}

template <class Vec>
Vec12 gather(const Vec& u, const std::array<int, 4>& t) {
  Vec12 ue;
  for (int a = 0; a < 4; ++a) ue.segment<3>(3 * a) = u.template segment<3>(3 * t[a]);
  return ue;
}

}  // namespace

namespace {
std::vector<int> all_tets(const TetMesh& m) {
  std::vector<int> v(m.num_tets());
  for (int e = 0; e < m.num_tets(); ++e) v[e] = e;
  return v;
}
}  // namespace

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points)
    : Simulation(spec, points, proto::Group(), all_tets(spec.mesh)) {}

Simulation::Simulation(const RunSpec& spec, PointEvaluator& points,
                       const proto::Group& coordinators, std::vector<int> owned_tets)
    : spec_(spec),
      evaluator_(points),
      self_(coordinators.valid() ? MPI_COMM_NULL : MPI_COMM_SELF),
      group_(coordinators.valid() ? coordinators : self_),
      owned_(std::move(owned_tets)),
      system_(spec, owned_, group_.rank(), group_.size()),
      mumps_(group_.raw(), system_.num_free()),
      pts_(tet_points(spec.mesh)) {
  const int ne = spec.mesh.num_tets();
  Q_.resize(ne);
  R_.resize(ne);
  for (int e = 0; e < ne; ++e) {
    Q_[e] = spec.frame.at(pts_[e].centroid);
    R_[e] = frame_rotation(Q_[e]);
  }
  const int n = system_.num_dofs();
  u_ = v_ = a_ = u_n_ = v_n_ = a_n_ = Eigen::VectorXd::Zero(n);
  Zbar_n_.assign(ne, Vec9::Zero());
  P_bar_.assign(ne, Vec9::Zero());
  jobs_.resize(owned_.size());
  values_.assign(system_.rows().size(), 0.0);
  if (system_.num_free() == 0)
    throw InputError("the Dirichlet conditions fix every degree of freedom: nothing to solve");
  mumps_.set_pattern(system_.rows(), system_.cols());
}

Vec3 Simulation::deformed_position(const Vec3& X) const {
  const MeshPoint p = locate_point(spec_.mesh, X);
  Vec3 x = X;
  for (int a = 0; a < 4; ++a) x += p.bary[a] * u_.segment<3>(3 * spec_.mesh.tets[p.tet][a]);
  return x;
}

void Simulation::agree_on_failure(const std::string& why) const {
  const int failed = group_.allreduce_max(static_cast<int>(!why.empty()));
  if (!failed) return;
  // The lowest failing coordinator's reason, for every coordinator.
  const int first = -group_.allreduce_max(why.empty() ? -group_.size() : -group_.rank());
  Bytes text;
  if (group_.rank() == first) text.assign(reinterpret_cast<const std::byte*>(why.data()),
                                          reinterpret_cast<const std::byte*>(why.data()) + why.size());
  group_.bcast(text, first);
  throw NumericalError(std::string(reinterpret_cast<const char*>(text.data()), text.size()));
}

std::vector<Vec9> Simulation::gather_point_stress() const {
  std::vector<double> flat(9 * static_cast<size_t>(spec_.mesh.num_tets()), 0.0);
  for (int e : owned_) std::copy(P_bar_[e].data(), P_bar_[e].data() + 9, flat.begin() + 9 * e);
  group_.reduce_sum(flat.data(), static_cast<int>(flat.size()), 0);
  std::vector<Vec9> P(spec_.mesh.num_tets());
  for (int e = 0; e < spec_.mesh.num_tets(); ++e) P[e] = Eigen::Map<const Vec9>(&flat[9 * e]);
  return P;
}

void Simulation::compute_jobs(int step, int iteration, double t_new, double dt, bool apply_update) {
  for (size_t k = 0; k < owned_.size(); ++k) {
    const int e = owned_[k];
    const auto& t = spec_.mesh.tets[e];
    const Vec9 Zbar = pts_[e].B * gather(u_, t);
    const Vec9 Zdot = spec_.dynamic ? Vec9(pts_[e].B * gather(v_, t)) : Vec9((Zbar - Zbar_n_[e]) / dt);
    // Non-finite first: NaN compares false, so it would pass as "inverted" below.
    if (!Zbar.allFinite() || !Zdot.allFinite())
      throw NumericalError(fmt::format("non-finite macro displacement gradient Z̄ or rate Ż̄ at "
                                       "element {}, t = {:.6g}, dt = {:.3g}",
                                       e, t_new, dt));
    const double J = (Mat3::Identity() + as_mat3(Zbar)).determinant();
    if (!std::isfinite(J))
      throw NumericalError(fmt::format("non-finite det F̄ at macro element {}, t = {:.6g}", e, t_new));
    if (!(J > 0.0))
      throw NumericalError(fmt::format("macro element {} inverted at t = {:.6g} (det F̄ = {:.3e})",
                                       e, t_new, J));
    proto::JobInput& job = jobs_[k];
    job.unit = e;
    job.step = step;
    job.iteration = iteration;
    job.time = t_new;
    job.dt = dt;
    job.apply_update = apply_update;
    job.force_refresh = 0;
    job.Zbar = R_[e] * Zbar;       // Z̄_μ = QᵀZ̄Q
    job.Zbar_dot = R_[e] * Zdot;
  }
}

bool Simulation::newton(int step, double t_new, double dt, StepRecord& rec) {
  const int nfree = system_.num_free();
  const int ndof = system_.num_dofs();
  const auto& prescribed = system_.prescribed();
  // Predictor: free DOFs keep their committed values; the prescribed increment Δū_D
  // enters the first iteration through the right-hand side (−S̄_fD Δū_D).
  Eigen::VectorXd du_D = Eigen::VectorXd::Zero(ndof);
  for (size_t k = 0; k < prescribed.size(); ++k)
    du_D[prescribed[k]] = system_.prescribed_value(k, t_new) - u_n_[prescribed[k]];
  const bool has_du_D = du_D.squaredNorm() > 0.0;
  const double c_mass = spec_.dynamic ? 1.0 / (spec_.beta * dt * dt) : 0.0;

  rec.residuals.clear();
  rec.micro_residuals.clear();
  std::vector<double> g(nfree);
  Eigen::VectorXd f_int(ndof), f_ext(ndof);
  for (int it = 1; it <= spec_.newton_max_iterations; ++it) {
    if (spec_.dynamic) {  // Newmark: a, v of the trial ū
      a_ = c_mass * (u_ - u_n_ - dt * v_n_) - (0.5 / spec_.beta - 1.0) * a_n_;
      v_ = v_n_ + dt * ((1.0 - spec_.gamma) * a_n_ + spec_.gamma * a_);
    }
    IterationTiming timing;
    timing.step = step;
    timing.iteration = it;
    const double t_begin = wall_seconds();
    // (a) Z̄ at the points, agreed valid on every coordinator, then (b–e)
    std::string why;
    try {
      compute_jobs(step, it, t_new, dt, it > 1);
    } catch (const NumericalError& e) {
      why = e.what();
    }
    agree_on_failure(why);
    evaluator_.evaluate(jobs_, results_);
    timing.micro_lc = wall_seconds() - t_begin;
    for (const auto& r : results_) {
      if (!why.empty()) break;
      if (r.failed) why = r.message;
      else if (!r.A_hom.allFinite() || !r.P_tilde.allFinite() || !r.P_bar.allFinite() ||
               !std::isfinite(r.r_norm) || !std::isfinite(r.r_ref))
        why = fmt::format("point {}: non-finite stress, tangent or residual at t = {:.6g}",
                          r.unit, t_new);
    }
    agree_on_failure(why);
    const double t_macro = wall_seconds();

    // (g) assemble S̄ and ḡ; f_int (with P̄) for the convergence test
    std::fill(values_.begin(), values_.end(), 0.0);
    std::fill(g.begin(), g.end(), 0.0);
    f_int.setZero();
    f_ext.setZero();
    double micro = 0.0;
    const bool first = it == 1 && has_du_D;
    for (size_t k = 0; k < owned_.size(); ++k) {
      const int e = owned_[k];
      const proto::JobOutput& r = results_[k];
      const TetPoint& p = pts_[e];
      const auto& t = spec_.mesh.tets[e];
      const Mat9 A = R_[e].transpose() * r.A_hom * R_[e];   // back to the global frame
      const Vec9 P_tilde = R_[e].transpose() * r.P_tilde;
      P_bar_[e] = R_[e].transpose() * r.P_bar;
      Mat12 Ke = p.volume * p.B.transpose() * A * p.B;      // |ē_k| B̄ᵀ 𝔸_hom B̄
      Vec12 fe = p.volume * p.B.transpose() * P_tilde;
      Vec12 fe_int = p.volume * p.B.transpose() * P_bar_[e];
      if (spec_.dynamic) {
        const Mat12 Me = tet_mass(spec_.density, p.volume);
        const Vec12 inertia = Me * gather(a_, t);
        Ke += c_mass * Me;
        fe += inertia;
        fe_int += inertia;
      }
      system_.add_tet(static_cast<int>(k), Ke, values_);
      const Vec12 lift = first ? Vec12(Ke * gather(du_D, t)) : Vec12::Zero();
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) {
          const int dof = 3 * t[a] + i;
          f_int[dof] += fe_int[3 * a + i];
          if (system_.eq(dof) >= 0) g[system_.eq(dof)] -= fe[3 * a + i] + lift[3 * a + i];
        }
      micro = std::max(micro, r.r_norm / r.r_ref);
    }
    const auto& tris = system_.pressure_triangles();
    for (size_t k = 0; k < tris.size(); ++k) {
      const PressureSpec& ps = spec_.pressure[tris[k].load];
      const double pr = ps.value * ramp_factor(ps.ramp, t_new, spec_.t_end);
      std::array<Vec3, 3> x;
      for (int a = 0; a < 3; ++a)
        x[a] = spec_.mesh.nodes[tris[k].nodes[a]] + u_.segment<3>(3 * tris[k].nodes[a]);
      Eigen::Matrix<double, 9, 1> f;
      Eigen::Matrix<double, 9, 9> dfdx;
      follower_pressure(x, pr, f, dfdx);
      const Eigen::Matrix<double, 9, 9> Kp = -dfdx;  // S̄ gets −∂f_ext/∂ū
      system_.add_triangle(static_cast<int>(k), Kp, values_);
      Eigen::Matrix<double, 9, 1> lift = Eigen::Matrix<double, 9, 1>::Zero();
      if (first)
        for (int a = 0; a < 3; ++a) lift += Kp.middleCols<3>(3 * a) * du_D.segment<3>(3 * tris[k].nodes[a]);
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) {
          const int dof = 3 * tris[k].nodes[a] + i;
          f_ext[dof] += f[3 * a + i];
          if (system_.eq(dof) >= 0) g[system_.eq(dof)] += f[3 * a + i] - lift[3 * a + i];
        }
    }

    // (i) convergence: true residual with P̄ on free DOFs, and every unit's ‖r‖ (sums
    // and maxima over all coordinators, identical on each)
    group_.allreduce_sum(f_int.data(), ndof);
    group_.allreduce_sum(f_ext.data(), ndof);
    micro = group_.allreduce_max(micro);
    double res2 = 0.0;
    for (int dof = 0; dof < ndof; ++dof)
      if (system_.eq(dof) >= 0) res2 += std::pow(f_ext[dof] - f_int[dof], 2);
    const double F_ref = std::max(f_int.norm(), f_ext.norm());
    const double res = F_ref > 0 ? std::sqrt(res2) / F_ref : std::sqrt(res2);
    if (!std::isfinite(res)) throw NumericalError(fmt::format("non-finite macro residual at t = {:.6g}", t_new));
    rec.residuals.push_back(res);
    rec.micro_residuals.push_back(micro);
    double work[3] = {0.0, 0.0, 0.0};  // GMRES iterations, refreshes, unit CPU seconds
    for (const auto& r : results_) {
      work[0] += r.gmres_iterations;
      work[1] += r.kind == proto::Refresh::refresh;
      work[2] += r.cpu_seconds;
    }
    group_.allreduce_sum(work, 3);
    rec.gmres_iterations += static_cast<int>(work[0]);
    rec.refreshes += static_cast<int>(work[1]);
    rec.micro_cpu_seconds += work[2];
    spdlog::debug("step {} t={:.6g} it {}: |R|/F = {:.3e}, max |r|/r_ref = {:.3e}", step, t_new,
                  it, res, micro);
    const bool converged = !first && res <= spec_.newton_rtol && micro <= spec_.micro_rtol;
    if (!converged) {
      // (h) S̄ Δū = ḡ on the coordinators (ḡ summed on the MUMPS host), Δū to all
      group_.reduce_sum(g.data(), nfree, 0);
      try {
        mumps_.factorize_and_solve(values_, g);
      } catch (const SingularMatrixError& e) {
        // Quasi-static iteration 1 assembles at the committed ū (points have no rate
        // dependence yet): the same matrix whatever the step, so no cut-back can help.
        if (it == 1 && !spec_.dynamic)
          throw SingularMatrixError(std::string(e.what()) + "; it is the matrix of the last "
                                    "converged state, so cutting the step back cannot help",
                                    true);
        throw;
      }
      group_.bcast(g.data(), nfree, 0);
      if (!std::all_of(g.begin(), g.end(), [](double x) { return std::isfinite(x); }))
        throw NumericalError(fmt::format("non-finite macro correction Δū at t = {:.6g}", t_new));
    }
    timing.macro = wall_seconds() - t_macro;
    timing.entire = wall_seconds() - t_begin;
    if (on_iteration_) on_iteration_(timing);
    if (converged) {
      rec.iterations += it;
      return true;
    }
    // (j) ū += Δū
    for (int dof = 0; dof < ndof; ++dof)
      if (system_.eq(dof) >= 0) u_[dof] += g[system_.eq(dof)];
    if (first) u_ += du_D;
  }
  rec.iterations += spec_.newton_max_iterations;
  return false;
}

void Simulation::commit(double t_new) {
  evaluator_.commit_step();
  for (int e : owned_) Zbar_n_[e] = pts_[e].B * gather(u_, spec_.mesh.tets[e]);
  u_n_ = u_;
  v_n_ = v_;
  a_n_ = a_;
  t_n_ = t_new;
}

void Simulation::rollback() {
  evaluator_.rollback_step();
  u_ = u_n_;
  v_ = v_n_;
  a_ = a_n_;
}

RunResult Simulation::run(const StepHook& on_step, const IterationHook& on_iteration) {
  on_iteration_ = on_iteration;
  RunResult result;
  const double dt_nominal = spec_.t_end / spec_.steps;
  for (int step = 0; step < spec_.steps; ++step) {
    StepRecord rec;
    rec.step = step;
    const double t0 = wall_seconds();
    const double t_target = (step + 1 == spec_.steps) ? spec_.t_end : (step + 1) * dt_nominal;
    int cut = 0;
    while (t_n_ < t_target - 1e-12 * spec_.t_end) {
      const double h = dt_nominal / std::ldexp(1.0, cut);
      const double t_new = std::min(t_n_ + h, t_target);
      std::string why;
      bool ok = false;
      try {
        ok = newton(step, t_new, t_new - t_n_, rec);
        if (!ok)
          why = fmt::format("Newton did not converge in {} iterations (last |R|/F = {:.3e}, "
                            "max unit |r|/r_ref = {:.3e})",
                            spec_.newton_max_iterations, rec.residuals.back(),
                            rec.micro_residuals.back());
      } catch (const SingularMatrixError& e) {
        if (e.at_committed_state) {
          rollback();
          result.error = fmt::format("step {} (t = {:.6g} → {:.6g}): {}", step, t_n_, t_new, e.what());
          result.history.push_back(rec);
          return result;
        }
        why = e.what();
      } catch (const NumericalError& e) {
        why = e.what();
      }
      if (ok) {
        commit(t_new);
        continue;
      }
      rollback();
      if (++cut > spec_.max_cutbacks) {
        result.error = fmt::format("step {} (t = {:.6g} → {:.6g}) failed after {} cutbacks: {}",
                                   step, t_n_, t_new, spec_.max_cutbacks, why);
        result.history.push_back(rec);
        return result;
      }
      ++rec.cutbacks;
      spdlog::warn("step {}: {}; cutting the step to dt = {:.4g}", step, why,
                   dt_nominal / std::ldexp(1.0, cut));
    }
    rec.time = t_n_;
    rec.wall_seconds = wall_seconds() - t0;
    result.newton_iterations += rec.iterations;
    result.steps = step + 1;
    result.history.push_back(rec);
    if (on_step) on_step(rec);
  }
  result.converged = true;
  return result;
}

}  // namespace fe2
