#include "worker/MicroUnit.h"

#include "worker/unit_equilibrium.h"

#include "common/cpu_timer.h"
#include "common/error.h"
#include "worker/abs_products.h"
#include "worker/micro_kernel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fe2 {

namespace {
/// Multiples of eps·‖|K||x|‖ a solve may leave in its residual (1: the backward-stable
/// scale; HardCases.UnitsAtHighFibreStretch stalls at 1.7× its GMRES target without it).
constexpr double kSolveFloorFactor = 1.0;
}  // namespace

namespace {
constexpr uint32_t kStateVersion = 4;  // 4: factor record (flag, then the factor); 3: point history
constexpr uint8_t kRebuildFactor = 0;  ///< the factor is rebuilt from K_factored_ when needed
constexpr uint8_t kStoredFactor = 1;   ///< the numeric factor follows (SparseFactor::save)
/// Larger factors are not stored: a unit's state travels to rank 0 in one MPI message,
/// whose count is an int (2 GiB).
constexpr double kMaxStoredFactorBytes = 1.5e9;

bool all_finite(const Eigen::Ref<const Eigen::MatrixXd>& m) { return m.allFinite(); }
}  // namespace

MicroUnit::MicroUnit(MicroModelPtr model)
    : model_(std::move(model)),
      factor_kind_(model_->initial_factor_kind()),
      policy_(model_->options().refresh, model_->options().N_t,
              2.0 * static_cast<double>(model_->pattern().nonZeros()), model_->options().solve_flop_cost),
      policy_committed_(policy_) {
  const int n = model_->num_dofs();
  w_ = Vec::Zero(n);
  dw1_ = Vec::Zero(n);
  w_committed_ = Vec::Zero(n);
  history_.assign(model_->history_size(), 0.0);  // empty unless some law keeps history
  model_->initial_history(history_);             // e.g. resting cells
  history_committed_ = history_;
  chi_ = Eigen::MatrixXd::Zero(n, 9);
  sys_.K = model_->zero_matrix();
  sys_.r = Vec::Zero(n);
  sys_.G = Eigen::MatrixXd::Zero(n, 9);
  sys_.H = Eigen::MatrixXd::Zero(9, n);
}

double MicroUnit::mean_active_tension() const {
  const MicroModel& m = *model_;
  double sum = 0.0, weight = 0.0;
  for (int e = 0; e < m.num_elements(); ++e) {
    const Material& law = m.material_of(e);
    const int slot = law.active_tension_slot();
    if (slot < 0) continue;
    const size_t h = static_cast<size_t>(law.history_size()), at = m.history_offset(e);
    for (int q = 0; q < 8; ++q) {
      const double w = m.geometry(e).weight[q];
      sum += w * history_[at + q * h + static_cast<size_t>(slot)];
      weight += w;
    }
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

void MicroUnit::assemble_at(const Vec& w, const Vec9& Zbar, System& sys,
                            std::vector<double>* history, std::vector<Vec9>* element_P) const {
  const MicroModel& m = *model_;
  const int n = m.num_dofs();
  const bool need_G = !m.symmetric();
  double* Kv = sys.K.valuePtr();
  std::fill(Kv, Kv + sys.K.nonZeros(), 0.0);
  sys.r.setZero(n);
  sys.H.setZero(9, n);
  Eigen::MatrixXd Gt;  // Gᵀ accumulated column-wise, only when 𝔸 lacks major symmetry
  if (need_G) Gt.setZero(9, n);
  sys.Abar.setZero();
  sys.Pbar.setZero();

  HexContribution c;
  Eigen::Matrix<double, 3, 8> w_e;
  if (element_P) element_P->assign(m.num_elements(), Vec9::Zero());
  const double inv_volume = m.inv_volume();
  std::vector<double> scratch;  // only for callers that keep no history of their own
  if (!history && m.history_size() > 0) {
    scratch.resize(m.history_size());
    history = &scratch;
  }
  HexPointContext point;  // filled per element only where the law reads it
  point.time = time_;
  point.dt = dt_;
  point.Zbar_dot = Zbar_dot_;
  point.Zbar_dot_coefficient = Zbar_dot_coefficient_;
  point.activation_time = activation_time_;
  for (int e = 0; e < m.num_elements(); ++e) {
    const auto& eq = m.element_equations(e);
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) {
        const int g = eq[hex_local(i, a)];
        w_e(i, a) = g >= 0 ? w[g] : 0.0;
      }
    const HexPointContext* context = nullptr;
    if (m.uses_context(e)) {
      // ẇ = (w − w_committed)/Δt: the backward-Euler (quasi-static) rate over the step,
      // as the coordinator's Ż̄ = (Z̄ − Z̄_n)/Δt, so that Ż = (Z − Z_n)/Δt at every Gauss
      // point. A job without a step (Δt = 0) has ẇ = 0.
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 8; ++a) {
          const int g = eq[hex_local(i, a)];
          point.w_dot_e(i, a) = g >= 0 && dt_ > 0.0 ? (w[g] - w_committed_[g]) / dt_ : 0.0;
        }
      if (history) {
        const size_t at = m.history_offset(e);
        point.history_committed = history_committed_.data() + at;
        point.history = history->data() + at;
      }
      context = &point;
    }
    // K's entries this element adds into are spread over 18 MB (at ≈ 26k DOF) and most
    // are not in cache: asked for now, they arrive while the kernel runs.
    const MicroModel::ElementScatter& sc = m.scatter(e);
    for (int b = 0; b < 8; ++b)
      for (int a = 0; a < 8; ++a) {
        const int p = sc.block[8 * a + b];
        if (p < 0) continue;
        for (int k = 0; k < 3; ++k) __builtin_prefetch(Kv + p + k * sc.stride[b], 1);
      }
    hex_contribution(m.geometry(e), inv_volume, w_e, Zbar, m.material_of(e), need_G, c, context);
    double* Hv = sys.H.data();
    for (int l = 0; l < 24; ++l) {
      const int gl = eq[l];
      if (gl < 0) continue;
      sys.r[gl] += c.r[l];
      for (int j = 0; j < 9; ++j) Hv[9 * static_cast<size_t>(gl) + j] += c.H(j, l);
      if (need_G) Gt.col(gl) += c.G.row(l).transpose();
    }
    // K: node block (a, b) of the element matrix, 3×3, into its place (MicroModel::scatter)
    for (int b = 0; b < 8; ++b) {
      const int stride = sc.stride[b];
      for (int a = 0; a < 8; ++a) {
        const int p = sc.block[8 * a + b];
        if (p < 0) continue;  // the pinned node
        for (int k = 0; k < 3; ++k)
          for (int i = 0; i < 3; ++i) Kv[p + k * stride + i] += c.K(hex_local(i, a), hex_local(k, b));
      }
    }
    sys.Abar += c.Abar;
    sys.Pbar += c.Pbar;
    if (element_P) (*element_P)[e] = c.Pbar;
  }
  // Into the existing storage: a fresh n×9 array per assembly costs page faults.
  if (need_G)
    sys.G = Gt.transpose();
  else
    sys.G = sys.H.transpose();
}

bool MicroUnit::refresh_due(const proto::JobInput& in) const {
  return in.force_refresh || next_refresh(in.step, in.iteration);
}

bool MicroUnit::next_refresh(int step, int iteration) const {
  return K_factored_.empty() || policy_.due(step, iteration);
}

size_t MicroUnit::state_bytes() const {
  // Mirrors serialize() field by field (a test holds the two equal).
  const size_t n = static_cast<size_t>(model_->num_dofs()), d = sizeof(double);
  const size_t len = sizeof(uint64_t);  // each array's length prefix
  size_t b = len + kind().size() + sizeof(uint32_t) + sizeof(uint64_t);
  b += 2 * (len + n * d) + (len + 9 * d) + 1;             // w, δw₁, Z̄, has_pending
  b += (len + 9 * n * d) + 1 + (len + K_factored_.size() * d);  // χ, factor kind, K
  b += (len + n * d) + (len + 9 * d);                     // committed w, Z̄
  b += 3 * d + sizeof(int);                               // policy, refreshes
  b += 3 * d + sizeof(int) + 1;                           // committed policy, refreshes
  b += 2 * (len + history_.size() * d);                   // history, committed history
  b += 1;                                                 // factor record: the rebuild flag
  if (refreshed_since_commit_)
    b += (len + committed_factor_.K_factored.size() * d) + (len + 9 * n * d) + 1;
  return b;
}

void MicroUnit::rebuild_factor() {
  // The factor of the very matrix it was made of: continuing after a migration is
  // then bit for bit the same as if the unit had never moved.
  SparseMatrix K = model_->pattern();
  std::copy(K_factored_.begin(), K_factored_.end(), K.valuePtr());
  factor_ = model_->make_factor(factor_kind_);
  factor_->factorize(K);
  factor_->compact();  // as the refresh left it
}

void MicroUnit::refresh() {
  if (!refreshed_since_commit_) {  // keep the committed factor state for a rollback
    committed_factor_ = {std::move(K_factored_), chi_, factor_kind_};
    refreshed_since_commit_ = true;
  }
  // (c1) factor K; LLᵀ falls back to LU under the automatic policy when K stops
  // being positive definite.
  K_factored_.assign(sys_.K.valuePtr(), sys_.K.valuePtr() + sys_.K.nonZeros());
  if (!factor_) factor_ = model_->make_factor(factor_kind_);
  try {
    factor_->factorize(sys_.K);
  } catch (const NumericalError&) {
    if (factor_kind_ != FactorKind::cholesky ||
        model_->options().factorization != MicroSolverOptions::Factorization::automatic)
      throw;
    factor_kind_ = FactorKind::lu;
    factor_ = model_->make_factor(factor_kind_);
    factor_->factorize(sys_.K);
  }
  // (c3) Eq. (6): χ = K⁻¹ G. The factor is exact for K unless it is single precision
  // or LLᵀ was forced on an unsymmetric K. A single-precision factor leaves χ at float
  // accuracy: rounds of block refinement χ ← χ + K̃⁻¹ (G − K χ), the unfinished columns
  // in one solve, take it to the tolerance for much less than nine GMRES runs. A column
  // is finished at the tolerance or at the solve's round-off floor (as GMRES judges it);
  // a round that does not lower every unfinished residual is dropped and ends them, and
  // GMRES finishes the columns still open.
  factor_->solve(sys_.G.data(), chi_.data(), 9);
  const auto& o = model_->options();
  const ResidualFloor floor = solve_floor();
  Eigen::VectorXd tol(9);
  for (int c = 0; c < 9; ++c) tol[c] = o.gmres_rtol * sys_.G.col(c).norm();
  Eigen::MatrixXd R = sys_.G - sys_.K * chi_;
  std::array<bool, 9> finished{};
  auto update_finished = [&](const Eigen::MatrixXd& X, const Eigen::VectorXd& r) {
    bool all = true;
    for (int c = 0; c < 9; ++c) {
      if (!finished[c]) finished[c] = r[c] <= tol[c] || r[c] <= floor(X.col(c));
      all = all && finished[c];
    }
    return all;
  };
  last_chi_solve_ = {};
  constexpr int kMaxRefinementRounds = 6;
  Eigen::VectorXd r = R.colwise().norm().transpose();
  for (int round = 0; !update_finished(chi_, r) && round < kMaxRefinementRounds; ++round) {
    Eigen::MatrixXd D(R.rows(), 9);
    factor_->solve(R.data(), D.data(), 9);
    for (int c = 0; c < 9; ++c)
      if (finished[c]) D.col(c).setZero();
    Eigen::MatrixXd chi_next = chi_ + D;
    Eigen::MatrixXd R_next = sys_.G - sys_.K * chi_next;
    const Eigen::VectorXd r_next = R_next.colwise().norm().transpose();
    bool lower = true;
    for (int c = 0; c < 9; ++c) lower = lower && (finished[c] || r_next[c] < r[c]);
    if (!lower) break;
    chi_ = std::move(chi_next);
    R = std::move(R_next);
    r = r_next;
    ++last_chi_solve_.refinement_rounds;
  }
  const LinearOp A = K_operator();
  const LinearOp M = preconditioner();
  for (int c = 0; c < 9; ++c) {
    if (finished[c]) continue;
    Vec x = chi_.col(c);
    const GmresResult res = gmres(A, M, sys_.G.col(c), x, tol[c], o.gmres_restart,
                                  o.gmres_max_iterations, floor);
    if (!res.converged)
      throw NumericalError(fmt::format(
          "micro unit: characteristic mode {} did not converge (GMRES residual {:.3e} after "
          "{} iterations, target {:.3e}, round-off floor {:.3e})",
          c, res.residual, res.iterations, tol[c], floor(x)));
    chi_.col(c) = x;
    last_chi_solve_.gmres_iterations += res.iterations;
  }
  factor_->compact();  // χ is solved: a binary16-kept factor is rounded only now
  policy_.refreshed(factor_->factor_flops(), factor_->solve_flops());
  ++refresh_count_;
}

double MicroUnit::residual_floor() {
  // F = I + Z̄ + ∇w is formed to a relative round-off eps·(1 + ‖Z̄‖): the same as moving
  // the nodes by ≈ eps·(1 + ‖Z̄‖)·h, to which the forces answer with |K| times that. No
  // iteration takes ‖r‖ below it (measured 3–30× under this bound at a cell/matrix
  // contrast of 1e3, where it is 1e-10 of r_ref: above a tight micro_rtol).
  const double h = std::cbrt(1.0 / (model_->inv_volume() * model_->num_elements()));
  const double nodes_moved = std::numeric_limits<double>::epsilon() * (1.0 + Zbar_.norm()) * h;
  if (!abs_row_sums_current_) {  // Step 1 made no product with this K
    abs_row_sums_ = abs_row_sums(sys_.K, model_->symmetric());
    abs_row_sums_current_ = true;
  }
  return nodes_moved * abs_row_sums_.norm();
}

LinearOp MicroUnit::K_operator() {
  return [this](const Vec& x, Vec& y) {
    if (abs_row_sums_current_) {
      y.noalias() = sys_.K * x;
    } else {  // the first product with this K also gives the residual floor's |K|𝟙
      times_and_abs_row_sums(sys_.K, x, y, abs_row_sums_, model_->symmetric());
      abs_row_sums_current_ = true;
    }
  };
}

LinearOp MicroUnit::preconditioner() const {
  return [this](const Vec& x, Vec& y) { factor_->solve(x.data(), y.data(), 1); };
}

ResidualFloor MicroUnit::solve_floor() const {
  // A backward-stable solve of K x = b leaves ‖b − Kx‖ ≈ eps·‖|K||x|‖; when K spans many
  // orders of magnitude (cells stiffened by an exponential law) that is above
  // gmres_rtol·‖b‖, and GMRES would spin to its iteration limit.
  return [this](const Vec& x) { return kSolveFloorFactor * std::numeric_limits<double>::epsilon() * abs_times(sys_.K, x).norm(); };
}

GmresResult MicroUnit::step1(double rtol, int max_iterations) {
  const auto& o = model_->options();
  const Vec b = -sys_.r;
  dw1_.setZero();
  const double bnorm = b.norm();
  if (bnorm == 0.0) return {0, 0.0, true};
  const LinearOp A = K_operator();
  const LinearOp M = preconditioner();
  return gmres(A, M, b, dw1_, rtol * bnorm, o.gmres_restart, max_iterations < 0 ? o.gmres_max_iterations : max_iterations,
               solve_floor());
}

void MicroUnit::settle(const proto::JobInput& job) {
  // Continuation in Z̄ from the committed state to the job's, each stage a quasi-static
  // equilibrium (Δt = 0: no rates, the cells' state does not advance) that is committed;
  // a stage that fails is halved. A fresh unit thrown at a finite Z̄ in one Newton update
  // inverts its cells (Step 1 linearizes about w = 0, the affine guess).
  constexpr double kRtol = 1e-8, kSmallest = 1.0 / 64.0;
  constexpr int kIterations = 20;
  const Vec9 from = Zbar_committed_, to = job.Zbar;
  double reached = 0.0, stage = 0.25;
  proto::JobInput q;
  q.step = job.step;
  q.time = job.time;
  q.activation_time = job.activation_time;
  while (reached < 1.0) {
    const double s = std::min(1.0, reached + stage);
    q.Zbar = from + s * (to - from);
    try {
      equilibrate(*this, q, kRtol, kIterations);
      reached = s;
      stage = std::min(2.0 * stage, 0.5);
    } catch (const NumericalError& e) {
      rollback_step();
      stage *= 0.5;
      if (stage < kSmallest)
        throw NumericalError(fmt::format("unit {}: settling afresh at Z̄ (|Z̄| = {:.3g}) failed at {:.0f} % of the "
                                         "way: {}",
                                         job.unit, to.norm(), 100.0 * reached, e.what()));
    }
  }
}

proto::JobOutput MicroUnit::iterate(const proto::JobInput& in) {
  proto::JobOutput out;
  out.unit = in.unit;
  const double t_start = thread_cpu_seconds();
  if (in.settle) settle(in);  // its cost is the job's

  // Accept the previous iteration: w += δw₁ − χ(Z̄_new − Z̄_old)   (Eq. 11)
  if (in.apply_update && has_pending_) {
    w_ += dw1_;
    if (model_->options().step4) w_.noalias() -= chi_ * (in.Zbar - Zbar_);
  }
  has_pending_ = false;
  Zbar_ = in.Zbar;
  time_ = in.time;
  dt_ = in.dt;
  Zbar_dot_ = in.Zbar_dot;
  Zbar_dot_coefficient_ = in.Zbar_dot_coefficient;
  activation_time_ = in.activation_time;

  {
    ScopedCpuTimer t(out.cpu_assembly);  // Fig. 5 (b)
    assemble_at(w_, Zbar_, sys_, &history_);
    abs_row_sums_current_ = false;
  }
  if (!all_finite(sys_.r) || !sys_.Pbar.allFinite() || !sys_.Abar.allFinite())
    throw NumericalError(fmt::format("micro unit {}: non-finite residual or stress at step {} "
                                     "iteration {}",
                                     in.unit, in.step, in.iteration));
  out.active_tension = mean_active_tension();
  const double r_norm = sys_.r.norm();
  const double r_ref = std::max(sys_.Pbar.norm(), model_->stress_floor()) * model_->node_scale();
  if (!std::isfinite(r_norm) || !std::isfinite(r_ref))  // overflow: inf <= inf must not converge
    throw NumericalError(fmt::format("micro unit {}: non-finite residual norm ({:.3e}, scale "
                                     "{:.3e}) at step {} iteration {}",
                                     in.unit, r_norm, r_ref, in.step, in.iteration));

  bool refreshed = refresh_due(in);
  if (refreshed) {
    ScopedCpuTimer t(out.cpu_refresh);
    refresh();
  } else if (!factor_) {  // arrived from another rank, rolled back or dropped: rebuild it
    ScopedCpuTimer t(out.cpu_refresh);
    rebuild_factor();
    out.factor_rebuilt = 1;
  }
  const double rtol = model_->options().step1_rtol(r_norm / r_ref);
  GmresResult res;
  {
    ScopedCpuTimer t(out.cpu_solve);  // Fig. 6 (c2)
    res = step1(rtol, refreshed ? -1 : policy_.stale_gmres_budget(model_->options().gmres_max_iterations));
  }
  if (!res.converged && !refreshed) {  // a stale preconditioner gave up (or cost a refresh): refresh once
    {
      ScopedCpuTimer t(out.cpu_refresh);
      refresh();
    }
    refreshed = true;
    ScopedCpuTimer t(out.cpu_solve);
    const int before = res.iterations;
    res = step1(rtol);
    res.iterations += before;
  }
  if (!res.converged)
    throw NumericalError(fmt::format(
        "micro unit {}: Step 1 GMRES did not converge at step {} iteration {} (residual "
        "{:.3e} after {} iterations, ‖r‖ = {:.3e})",
        in.unit, in.step, in.iteration, res.residual, res.iterations, sys_.r.norm()));
  if (!refreshed) policy_.reused(res.iterations);
  has_pending_ = true;

  out.A_hom = sys_.Abar - sys_.H * chi_;      // Eq. (7)
  out.P_tilde = sys_.Pbar + sys_.H * dw1_;    // Eq. (9)
  if (!out.A_hom.allFinite() || !out.P_tilde.allFinite())
    throw NumericalError(fmt::format("micro unit {}: non-finite homogenized tangent or condensed "
                                     "stress at step {} iteration {}",
                                     in.unit, in.step, in.iteration));
  out.P_bar = sys_.Pbar;
  out.r_norm = r_norm;
  out.r_ref = r_ref;
  out.r_floor = residual_floor();
  out.gmres_iterations = res.iterations;
  out.kind = refreshed ? proto::Refresh::refresh : proto::Refresh::reuse;
  out.excess_flops = refreshed ? 0.0 : policy_.excess_flops(res.iterations);
  out.refresh_flops = policy_.refresh_flops();
  out.cpu_seconds = thread_cpu_seconds() - t_start;
  return out;
}

void MicroUnit::commit_step() {
  // The converged iteration's δw₁ is not applied (paper Fig. 5 (i): converged, go to
  // the next step), so the state to keep is the assembled one.
  has_pending_ = false;
  w_committed_ = w_;
  Zbar_committed_ = Zbar_;
  policy_committed_ = policy_;
  refresh_count_committed_ = refresh_count_;
  history_committed_ = history_;
  refreshed_since_commit_ = false;
  committed_factor_ = FactorState{};
}

void MicroUnit::rollback_step() {
  has_pending_ = false;
  w_ = w_committed_;
  Zbar_ = Zbar_committed_;
  policy_ = policy_committed_;
  refresh_count_ = refresh_count_committed_;
  history_ = history_committed_;
  if (refreshed_since_commit_) {
    // Back to the committed factor: rebuilt from its matrix on the next job that reuses
    // it (bit for bit, as after a migration), or replaced if that job refreshes.
    K_factored_ = std::move(committed_factor_.K_factored);
    chi_ = std::move(committed_factor_.chi);
    factor_kind_ = committed_factor_.kind;
    committed_factor_ = FactorState{};
    refreshed_since_commit_ = false;
    factor_.reset();
  }
}

void MicroUnit::serialize_for_checkpoint(Bytes& out, bool with_factor) const {
  ByteWriter b(out);
  b.put_string(kind());
  b.put(kStateVersion);
  b.put(model_->fingerprint());
  const size_t n = static_cast<size_t>(model_->num_dofs());
  b.put_array(w_.data(), n);
  b.put_array(dw1_.data(), n);
  b.put_array(Zbar_.data(), 9);
  b.put<uint8_t>(has_pending_);
  b.put_array(chi_.data(), 9 * n);
  b.put<uint8_t>(factor_kind_ == FactorKind::lu);
  b.put_array(K_factored_.data(), K_factored_.size());
  b.put_array(w_committed_.data(), n);
  b.put_array(Zbar_committed_.data(), 9);
  policy_.write(b);
  b.put(refresh_count_);
  policy_committed_.write(b);
  b.put(refresh_count_committed_);
  b.put<uint8_t>(refreshed_since_commit_);
  if (refreshed_since_commit_) {
    b.put_array(committed_factor_.K_factored.data(), committed_factor_.K_factored.size());
    b.put_array(committed_factor_.chi.data(), 9 * n);
    b.put<uint8_t>(committed_factor_.kind == FactorKind::lu);
  }
  b.put_array(history_.data(), history_.size());
  b.put_array(history_committed_.data(), history_committed_.size());
  // The factor goes along only if asked, present and savable; it is the factor of
  // K_factored_ (checkpoints are taken at step boundaries, after commit).
  const bool store = with_factor && factor_ && factor_->ready() && factor_->savable() && !K_factored_.empty() &&
                     factor_->factor_bytes() <= kMaxStoredFactorBytes;
  b.put<uint8_t>(store ? kStoredFactor : kRebuildFactor);
  if (store) factor_->save(b);
}

void MicroUnit::deserialize(const Bytes& in) {
  ByteReader b(in, "micro unit state");
  if (b.get_string() != kind()) throw Error("micro unit state: not a micro unit");
  const auto version = b.get<uint32_t>();
  if (version != kStateVersion && version != 3)  // 3: as 4, without the factor record
    throw Error(fmt::format("micro unit state: version {}, expected 3 or {} (a state written by "
                            "another build of fe2heart)",
                            version, kStateVersion));
  if (b.get<uint64_t>() != model_->fingerprint())
    throw Error("micro unit state: it belongs to a different unit model (fingerprint differs)");
  const size_t n = static_cast<size_t>(model_->num_dofs());
  b.get_array_into(w_.data(), n);
  b.get_array_into(dw1_.data(), n);
  b.get_array_into(Zbar_.data(), 9);
  has_pending_ = b.get<uint8_t>() != 0;
  b.get_array_into(chi_.data(), 9 * n);
  factor_kind_ = b.get<uint8_t>() ? FactorKind::lu : FactorKind::cholesky;
  K_factored_ = b.get_array<double>();
  if (!K_factored_.empty() && K_factored_.size() != static_cast<size_t>(sys_.K.nonZeros()))
    throw Error("micro unit state: stored factor matrix has the wrong size");
  b.get_array_into(w_committed_.data(), n);
  b.get_array_into(Zbar_committed_.data(), 9);
  policy_.read(b);
  refresh_count_ = b.get<int>();
  policy_committed_.read(b);
  refresh_count_committed_ = b.get<int>();
  refreshed_since_commit_ = b.get<uint8_t>() != 0;
  committed_factor_ = FactorState{};
  if (refreshed_since_commit_) {
    committed_factor_.K_factored = b.get_array<double>();
    if (!committed_factor_.K_factored.empty() &&
        committed_factor_.K_factored.size() != static_cast<size_t>(sys_.K.nonZeros()))
      throw Error("micro unit state: stored committed factor matrix has the wrong size");
    committed_factor_.chi.resize(static_cast<Eigen::Index>(n), 9);
    b.get_array_into(committed_factor_.chi.data(), 9 * n);
    committed_factor_.kind = b.get<uint8_t>() ? FactorKind::lu : FactorKind::cholesky;
  }
  b.get_array_into(history_.data(), history_.size());
  b.get_array_into(history_committed_.data(), history_committed_.size());
  // Without a stored factor, it is rebuilt from K_factored_ only if the next job reuses
  // it: a unit migrated at a refresh boundary costs no extra factorization.
  factor_.reset();
  const uint8_t record = version >= 4 ? b.get<uint8_t>() : kRebuildFactor;
  if (record == kStoredFactor) {
    if (K_factored_.empty()) throw Error("micro unit state: a stored factor without the matrix it was made of");
    auto factor = model_->make_factor(factor_kind_);
    factor->load(b, model_->pattern());  // checked against K's pattern, not refactored
    factor_ = std::move(factor);
  } else if (record != kRebuildFactor) {
    throw Error(fmt::format("micro unit state: factor record {}, expected {} (rebuild) or {} (stored)", record,
                            kRebuildFactor, kStoredFactor));
  }
  if (!b.at_end()) throw Error("micro unit state: trailing bytes");
}

}  // namespace fe2
