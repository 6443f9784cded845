#include "coordinator/macro/CavityPressureTerm.h"

#include "common/error.h"
#include "common/fem/follower_pressure.h"
#include "common/fem/vertex_volumes.h"
#include "common/mesh/cavity_volume.h"
#include "coordinator/macro/FluidSetup.h"

#include <algorithm>
#include <set>

namespace fe2 {

namespace {

/// The circulation cavities named by valve rings of two-way blood.
std::set<int> blood_cavities(const RunSpec& spec) {
  std::set<int> named;
  if (!spec.fluid || !spec.fluid->two_way) return named;
  for (const FluidBoundary& b : spec.fluid->boundaries)
    if (b.valve) named.insert(b.valve->cavity);
  return named;
}

/// The fluid regions that touch the surface `tris`: the blood of that cavity.
std::set<int> regions_touching(const RunSpec& spec, const std::vector<std::array<int, 3>>& tris) {
  std::set<std::array<int, 3>> faces;
  for (auto t : tris) {
    std::sort(t.begin(), t.end());
    faces.insert(t);
  }
  const std::vector<int>& fluid = spec.fluid->regions;
  std::set<int> touching;
  for (int e = 0; e < spec.mesh.num_tets(); ++e) {
    const int region = spec.mesh.region[static_cast<size_t>(e)];
    if (std::find(fluid.begin(), fluid.end(), region) == fluid.end()) continue;
    for (int opp = 0; opp < 4; ++opp) {
      std::array<int, 3> f{};
      for (int a = 0, k = 0; a < 4; ++a)
        if (a != opp) f[static_cast<size_t>(k++)] = spec.mesh.tets[static_cast<size_t>(e)][static_cast<size_t>(a)];
      std::sort(f.begin(), f.end());
      if (faces.count(f)) touching.insert(region);
    }
  }
  return touching;
}

}  // namespace

CavityPressureTerm::CavityPressureTerm(const RunSpec& spec, const MacroPartition& partition)
    : spec_(spec), circulation_(*spec.circulation), owns_rows_(partition.owns_globals()) {
  const std::set<int> with_blood = blood_cavities(spec);
  committed_.assign(circulation_.state_size(), 0.0);
  circulation_.initial_state(committed_);
  current_ = committed_;
  p_fill_ = circulation_.filling_pressures(committed_);
  const Eigen::VectorXd u0 = Eigen::VectorXd::Zero(3 * spec.mesh.num_nodes());
  for (int c : spec.coupled_cavities) {
    Cavity cav;
    cav.surface = spec.cavities[c].second;
    cav.triangles = partition.owned_faces(spec.mesh, spec.mesh.faces.at(cav.surface));
    const CavityVolume v = cavity_volume(spec.mesh, cav.surface, u0);
    for (const auto& [dof, _] : v.dV_du) cav.volume_nodal.push_back(dof);
    V_ref_.push_back(v.volume);
    cav.blood = with_blood.count(static_cast<int>(cavities_.size())) > 0;
    if (cav.blood) {
      const std::set<int> regions = regions_touching(spec, spec.mesh.faces.at(cav.surface));
      if (regions.empty())
        throw InputError(fmt::format("/cavities/{}: surface '{}' touches no fluid region, expected the blood "
                                     "whose valve rings name this cavity to fill it",
                                     spec.cavities[c].first, cav.surface));
      for (int e : partition.elements())
        if (regions.count(spec.mesh.region[static_cast<size_t>(e)])) cav.blood_elements.push_back(e);
      cav.triangles.clear();  // the blood loads the wall
    }
    cavities_.push_back(std::move(cav));
  }
  V_n_ = V_ref_;
}

void CavityPressureTerm::declare(MacroSystem& system) {
  u_ = &system.field("displacement");
  pc_ = &system.field("cavity_pressure");
  rings_ = system.fields().find("fluid_flux_pressure");
  for (size_t i = 0; i < cavities_.size(); ++i) cavity_dofs_.push_back(pc_->global_dof(static_cast<int>(i)));
  for (size_t i = 0; i < cavities_.size(); ++i) {
    Cavity& cav = cavities_[i];
    cav.dof = cavity_dofs_[i];
    for (const auto& tri : cav.triangles) {
      Face f;
      f.nodes = spec_.mesh.face_nodes(tri);
      f.dofs = u_->node_dofs(f.nodes);
      f.local_uu = system.declare_local(f.dofs);
      f.local_up = system.declare_local(f.dofs, {cav.dof});
      cav.faces.push_back(std::move(f));
    }
    if (cav.blood) {
      const Field& p = system.field("fluid_pressure");
      for (int e : cav.blood_elements) {
        std::vector<int> dofs{cav.dof};
        for (int a : spec_.mesh.tets[static_cast<size_t>(e)]) dofs.push_back(p.node_dof(a));
        cav.blood_local.push_back(system.declare_local({cav.dof}, dofs));
        cav.blood_dofs.push_back(std::move(dofs));
      }
      continue;  // no volume row
    }
    if (!owns_rows_) continue;
    // cavity_volume() numbers ū node-major over the whole mesh (3a + i).
    for (int d : cav.volume_nodal) cav.volume_dofs.push_back(u_->node_dof(d / 3, d % 3));
    cav.local_pu = system.declare_local({cav.dof}, cav.volume_dofs);
  }
  if (owns_rows_) local_pp_ = system.declare_local(cavity_dofs_);
}

void CavityPressureTerm::assemble(const MacroState& state, MacroAssembly& out) {
  const int n = static_cast<int>(cavities_.size());
  std::vector<double> p(n);
  for (int i = 0; i < n; ++i) p[i] = state.x[cavity_dofs_[i]];
  const bool inflating = spec_.inflating(state.time);
  inflating_ = inflating;
  // Every coordinator advances the (small) circulation, so that its flows and valve
  // states are known wherever a term reads them (valve rings); the rows are the owner's.
  Circulation::ValvePorts ports;
  if (ports_ && rings_)  // asked at every assembly (the rings' states follow it)
    ports = ports_(std::span<const double>(state.x.data() + rings_->offset(), static_cast<size_t>(rings_->size())));
  flows_ = inflating ? circulation_.at_rest(0.0, p, committed_)
                     : circulation_.step(state.time, state.dt, p, committed_, current_, ports);
  assemble_blood_rows(state, out);
  Eigen::VectorXd f1;
  Eigen::MatrixXd dfdx1;
  std::vector<Vec3> x;
  for (int i = 0; i < n; ++i) {
    Cavity& cav = cavities_[i];
    // The load is linear in p_c: with the unit-pressure force f₁ (= −∫N n da),
    // f_ext = p_c f₁, ∂f_ext/∂ū = p_c ∂f₁/∂ū and ∂f_ext/∂p_c = f₁.
    for (const Face& f : cav.faces) {
      x.clear();
      for (int a : f.nodes) x.push_back(spec_.mesh.nodes[a] + state.x.segment<3>(u_->node_dof(a)));
      follower_pressure(x, 1.0, f1, dfdx1);
      out.add_tangent(f.local_uu, -p[i] * dfdx1);  // R = f_int − f_ext
      out.add_tangent(f.local_up, -f1);
      out.add_external(f.dofs, p[i] * f1);
    }
    if ((!owns_rows_ && !inflating) || (cav.blood && !inflating)) continue;
    const CavityVolume v = cavity_volume(spec_.mesh, cav.surface, u_->at_every_node(state.x, spec_.mesh.num_nodes()));
    if (inflating) {
      // The atrium holds its pressure while the wall inflates: what the cavity takes in
      // comes through its open inflow valve (blood in the cavity enters by the mitral ring).
      if (state.dt > 0.0) flows_.Q_in[i] = flows_.Q_net[i] = (v.volume - V_n_[i]) / state.dt;
      flows_.inflow_open[i] = true;
      continue;
    }
    if (cav.blood) continue;  // its rows: assemble_blood_rows
    // R_c = V_c(ū) − V_c,n − Δt Q_net,c(p)
    Eigen::MatrixXd row(1, static_cast<Eigen::Index>(v.dV_du.size()));
    for (size_t k = 0; k < v.dV_du.size(); ++k) row(0, static_cast<Eigen::Index>(k)) = v.dV_du[k].second;
    out.add_tangent(cav.local_pu, row);
    out.add_internal({cav.dof}, Eigen::VectorXd::Constant(1, v.volume - V_n_[i] - state.dt * flows_.Q_net[i]));
  }
  if (!owns_rows_) return;
  if (inflating) {
    assemble_inflation(state.time, p, out);
    return;
  }
  Eigen::MatrixXd Kpp(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) Kpp(i, j) = cavities_[static_cast<size_t>(i)].blood ? 0.0 : -state.dt * flows_.dQ(i, j);
  out.add_tangent(local_pp_, Kpp);
}

void CavityPressureTerm::assemble_blood_rows(const MacroState& state, MacroAssembly& out) const {
  if (spec_.inflating(state.time)) return;  // p_c prescribed: assemble_inflation
  for (const Cavity& cav : cavities_)
    for (size_t k = 0; k < cav.blood_elements.size(); ++k) {
      // ∫_e (p_c − p) dV = Σ_b m_b (p_c − p_b), m_b = ∫N_b dV (reference)
      const Eigen::Vector4d m = vertex_volumes(spec_.mesh, cav.blood_elements[k]);
      const std::vector<int>& dofs = cav.blood_dofs[k];
      double r = 0.0;
      Eigen::MatrixXd K(1, 5);
      K(0, 0) = m.sum();
      for (int b = 0; b < 4; ++b) {
        r += m[b] * (state.x[dofs[0]] - state.x[dofs[static_cast<size_t>(b) + 1]]);
        K(0, b + 1) = -m[b];
      }
      out.add_internal({dofs[0]}, Eigen::VectorXd::Constant(1, r));
      out.add_tangent(cav.blood_local[k], K);
    }
}

void CavityPressureTerm::assemble_inflation(double t, const std::vector<double>& p, MacroAssembly& out) const {
  // R_c = (V_ref / p_s)(p_c − p_fill (t − t_start)/(−t_start)): linear, exact in one step.
  const int n = static_cast<int>(cavities_.size());
  const double ramp = (t - spec_.t_start) / -spec_.t_start;
  Eigen::MatrixXd Kpp = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double s = V_ref_[i] / std::max(p_fill_[i], 1000.0);
    Kpp(i, i) = s;
    out.add_internal({cavity_dofs_[i]}, Eigen::VectorXd::Constant(1, s * (p[i] - p_fill_[i] * ramp)));
  }
  out.add_tangent(local_pp_, Kpp);
}

void CavityPressureTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (!owns_rows_ || field.id() != pc_->id()) return;
  for (size_t i = 0; i < V_ref_.size(); ++i) scale[static_cast<Eigen::Index>(i)] += V_ref_[i];
}

void CavityPressureTerm::commit(const MacroState& state) {
  if (spec_.inflating(state.time)) {
    // The circulation stood still; only the cavity pressures it last saw follow the wall.
    std::vector<double> p;
    for (int dof : cavity_dofs_) p.push_back(state.x[dof]);
    circulation_.set_cavity_pressures(committed_, p);
    current_ = committed_;
  } else {
    committed_ = current_;
  }
  committed_flows_ = flows_;
  const Eigen::VectorXd u = u_->at_every_node(state.x, spec_.mesh.num_nodes());
  for (size_t i = 0; i < cavities_.size(); ++i) V_n_[i] = cavity_volume(spec_.mesh, cavities_[i].surface, u).volume;
}

void CavityPressureTerm::rollback() {
  current_ = committed_;
  flows_ = committed_flows_;  // what the rings' states are decided from at the retry's start
}

void CavityPressureTerm::save(ByteWriter& w) const {
  w.put_array(committed_.data(), committed_.size());
  w.put_array(V_n_.data(), V_n_.size());
}

void CavityPressureTerm::restore(ByteReader& r) {
  committed_ = r.get_array<double>(static_cast<int64_t>(committed_.size()));
  V_n_ = r.get_array<double>(static_cast<int64_t>(V_n_.size()));
  current_ = committed_;
}

}  // namespace fe2
