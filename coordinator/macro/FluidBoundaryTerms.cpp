#include "coordinator/macro/FluidBoundaryTerms.h"

#include "common/fem/vertex_volumes.h"
#include "common/fluid/fluid_boundary.h"
#include "coordinator/macro/gather.h"

#include <algorithm>

namespace fe2 {

namespace {

/// The partition's triangles of the face sets that bound a fluid element (a set may
/// reach past the fluid, e.g. a box face through wall and fluid).
std::vector<FluidFace> owned_faces_of(const TetMesh& mesh, const MacroPartition& partition,
                                      const std::vector<std::string>& sets, const std::vector<int>& regions) {
  std::vector<FluidFace> faces;
  for (size_t k = 0; k < sets.size(); ++k) {
    const auto tris = partition.owned_faces(mesh, mesh.faces.at(sets[k]));
    const std::vector<int> tets = face_elements(mesh, tris);
    for (size_t t = 0; t < tris.size(); ++t)
      if (std::find(regions.begin(), regions.end(), mesh.region[tets[t]]) != regions.end())
        faces.push_back({mesh.face_nodes(tris[t]), static_cast<int>(k)});
  }
  return faces;
}

template <class B>
std::vector<std::string> set_names(const std::vector<B>& boundaries) {
  std::vector<std::string> names;
  for (const B& b : boundaries) names.push_back(b.set);
  return names;
}

}  // namespace

void fluid_face_geometry(const TetMesh& mesh, const Field* d, const std::vector<int>& nodes, const MacroState& s,
                         Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& w) {
  const int m = static_cast<int>(nodes.size());
  x.resize(3, m);
  w = Eigen::Matrix3Xd::Zero(3, m);
  for (int a = 0; a < m; ++a) {
    x.col(a) = mesh.nodes[nodes[a]];
    if (d && d->has_node(nodes[a])) {
      x.col(a) += s.x.segment<3>(d->node_dof(nodes[a]));
      w.col(a) = s.v.segment<3>(d->node_dof(nodes[a]));
    }
  }
}

std::vector<double> face_fluxes(const TetMesh& mesh, const Field& v, const Field* d, const std::vector<FluidFace>& faces,
                                size_t boundaries, const MacroState& s) {
  std::vector<double> Q(boundaries, 0.0);
  Eigen::Matrix3Xd x, w;
  for (const FluidFace& f : faces) {
    fluid_face_geometry(mesh, d, f.nodes, s, x, w);
    const Eigen::Matrix3Xd S = face_normal_integrals(mesh.order(), x);
    for (size_t a = 0; a < f.nodes.size(); ++a)
      Q[f.boundary] += (s.x.segment<3>(v.node_dof(f.nodes[a])) - w.col(static_cast<Eigen::Index>(a)))
                           .dot(S.col(static_cast<Eigen::Index>(a)));
  }
  return Q;
}

// --- open (pressure) boundaries

OpenBoundaryTerm::OpenBoundaryTerm(const TetMesh& mesh, const MacroPartition& partition,
                                   const std::vector<int>& regions, std::vector<Boundary> boundaries, double density)
    : mesh_(mesh), boundaries_(std::move(boundaries)), density_(density),
      faces_(owned_faces_of(mesh, partition, set_names(boundaries_), regions)) {}

void OpenBoundaryTerm::declare(MacroSystem& system) {
  v_ = &system.field("fluid_velocity");
  d_ = system.fields().find("mesh_displacement");
  for (const FluidFace& f : faces_) {
    dofs_.push_back(v_->node_dofs(f.nodes));
    local_.push_back(boundaries_[f.boundary].backflow > 0.0 ? system.declare_local(dofs_.back()) : -1);
  }
}

void OpenBoundaryTerm::assemble(const MacroState& state, MacroAssembly& out) {
  const int order = mesh_.order();
  Eigen::Matrix3Xd x, w;
  Eigen::VectorXd R;
  Eigen::MatrixXd K;
  for (size_t k = 0; k < faces_.size(); ++k) {
    const Boundary& b = boundaries_[faces_[k].boundary];
    fluid_face_geometry(mesh_, d_, faces_[k].nodes, state, x, w);
    if (b.pressure) {  // t = −P n: f_ext,a = −P ∫ N_a n da
      const Eigen::Matrix3Xd S = face_normal_integrals(order, x);
      out.add_external(dofs_[k], -b.pressure(state.time) * Eigen::Map<const Eigen::VectorXd>(S.data(), S.size()));
    } else {  // f_ext,a = t ∫ N_a da
      const Eigen::VectorXd S = face_shape_integrals(order, x);
      const Vec3 t = b.traction(state.time);
      Eigen::VectorXd f(3 * S.size());
      for (Eigen::Index a = 0; a < S.size(); ++a) f.segment<3>(3 * a) = S[a] * t;
      out.add_external(dofs_[k], f);
    }
    if (local_[k] < 0) continue;
    const Eigen::VectorXd v = gather(state.x, dofs_[k]);
    backflow_face(order, density_, b.backflow, x, Eigen::Map<const Eigen::Matrix3Xd>(v.data(), 3, v.size() / 3), w, R,
                  &K);
    out.add_internal(dofs_[k], R);
    out.add_tangent(local_[k], K);
  }
}

void OpenBoundaryTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  const std::vector<double> Q = face_fluxes(mesh_, *v_, d_, faces_, boundaries_.size(), state);
  std::vector<FaceEnergyFlux> energy(boundaries_.size());
  Eigen::Matrix3Xd x, w, v;
  for (size_t k = 0; k < faces_.size(); ++k) {
    const FluidFace& f = faces_[k];
    fluid_face_geometry(mesh_, d_, f.nodes, state, x, w);
    v.resize(3, static_cast<Eigen::Index>(f.nodes.size()));
    for (size_t a = 0; a < f.nodes.size(); ++a)
      v.col(static_cast<Eigen::Index>(a)) = state.x.segment<3>(v_->node_dof(f.nodes[a]));
    const FaceEnergyFlux e = face_energy_flux(mesh_.order(), density_, boundaries_[f.boundary].backflow, x, v, w);
    energy[f.boundary].kinetic += e.kinetic;
    energy[f.boundary].backflow += e.backflow;
  }
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    out.push_back({"flux:" + boundaries_[b].set, Q[b]});
    out.push_back({"kinetic_flux:" + boundaries_[b].set, energy[b].kinetic});
    out.push_back({"backflow_power:" + boundaries_[b].set, energy[b].backflow});
  }
}

// --- flux constraints

FluxConstraintTerm::FluxConstraintTerm(const TetMesh& mesh, const MacroPartition& partition,
                                       const std::vector<int>& regions, std::vector<Boundary> boundaries)
    : mesh_(mesh), owns_globals_(partition.owns_globals()), boundaries_(std::move(boundaries)),
      faces_(owned_faces_of(mesh, partition, set_names(boundaries_), regions)) {}

void FluxConstraintTerm::declare(MacroSystem& system) {
  v_ = &system.field("fluid_velocity");
  d_ = system.fields().find("mesh_displacement");
  lambda_ = &system.field("fluid_flux_pressure");
  for (const FluidFace& f : faces_) {
    std::vector<int> dofs = v_->node_dofs(f.nodes);
    dofs.push_back(lambda_->global_dof(f.boundary));
    dofs_.push_back(std::move(dofs));
    local_.push_back(system.declare_local(dofs_.back()));
  }
  cavity_pressure_ = system.fields().find("cavity_pressure");
  if (owns_globals_)
    for (size_t b = 0; b < boundaries_.size(); ++b) {
      const int dof = lambda_->global_dof(static_cast<int>(b));
      local_shut_.push_back(boundaries_[b].active ? system.declare_local({dof}) : -1);
      std::vector<int> columns{dof};
      if (boundaries_[b].coupling && cavity_pressure_) {
        for (int c = 0; c < cavity_pressure_->size(); ++c) columns.push_back(cavity_pressure_->global_dof(c));
        for (size_t other = 0; other < boundaries_.size(); ++other)
          if (other != b && boundaries_[other].coupling) columns.push_back(lambda_->global_dof(static_cast<int>(other)));
      }
      local_coupled_.push_back(columns.size() > 1 ? system.declare_local({dof}, columns) : -1);
      coupled_columns_.push_back(std::move(columns));
    }
  // The reference areas of the whole rings, whichever coordinator owns their faces (the
  // scale of a ring's row while it holds a pressure).
  area_.assign(boundaries_.size(), 0.0);
  for (size_t b = 0; b < boundaries_.size(); ++b)
    for (const auto& tri : mesh_.faces.at(boundaries_[b].set)) {
      const std::vector<int> nodes = mesh_.face_nodes(tri);
      Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(nodes.size()));
      for (size_t a = 0; a < nodes.size(); ++a) x.col(static_cast<Eigen::Index>(a)) = mesh_.nodes[nodes[a]];
      area_[b] += face_normal_integrals(mesh_.order(), x).rowwise().sum().norm();
    }
}

void FluxConstraintTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (field.id() != lambda_->id()) return;
  for (const FluidFace& f : faces_) {
    Eigen::Matrix3Xd x(3, static_cast<Eigen::Index>(f.nodes.size()));
    for (size_t a = 0; a < f.nodes.size(); ++a) x.col(static_cast<Eigen::Index>(a)) = mesh_.nodes[f.nodes[a]];
    scale[f.boundary] += face_normal_integrals(mesh_.order(), x).rowwise().sum().norm();
  }
}

void FluxConstraintTerm::assemble(const MacroState& state, MacroAssembly& out) {
  std::vector<char> active(boundaries_.size());
  std::vector<RingCoupling> coupling(boundaries_.size());
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    active[b] = !boundaries_[b].active || boundaries_[b].active();
    if (boundaries_[b].coupling) coupling[b] = boundaries_[b].coupling();
  }
  Eigen::Matrix3Xd x, w;
  for (size_t k = 0; k < faces_.size(); ++k) {
    fluid_face_geometry(mesh_, d_, faces_[k].nodes, state, x, w);
    const Eigen::Matrix3Xd S = face_normal_integrals(mesh_.order(), x);
    const Eigen::Map<const Eigen::VectorXd> s(S.data(), S.size());
    const int nv = static_cast<int>(S.size());
    Eigen::VectorXd R = Eigen::VectorXd::Zero(nv + 1);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nv + 1, nv + 1);
    if (active[static_cast<size_t>(faces_[k].boundary)]) {
      const Eigen::VectorXd v = gather(state.x, dofs_[k]).head(nv);
      const double lambda = state.x[dofs_[k].back()];
      R.head(nv) = lambda * s;
      K.col(nv).head(nv) = s;
      if (const Boundary& b = boundaries_[static_cast<size_t>(faces_[k].boundary)]; b.backflow > 0.0) {
        Eigen::VectorXd Rb;
        Eigen::MatrixXd Kb;
        backflow_face(mesh_.order(), b.density, b.backflow, x, Eigen::Map<const Eigen::Matrix3Xd>(v.data(), 3, nv / 3), w,
                      Rb, &Kb);
        R.head(nv) += Rb;
        K.topLeftCorner(nv, nv) += Kb;
      }
      if (coupling[static_cast<size_t>(faces_[k].boundary)].holds_pressure_of < 0) {  // a flux row
        R[nv] = (v - Eigen::Map<const Eigen::VectorXd>(w.data(), w.size())).dot(s);
        K.row(nv).head(nv) = s.transpose();
      }
    }
    out.add_internal(dofs_[k], R);
    out.add_tangent(local_[k], K);
  }
  if (!owns_globals_) return;
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    const int dof = lambda_->global_dof(static_cast<int>(b));
    const RingCoupling& rc = coupling[b];
    if (local_coupled_[b] >= 0 && (active[b] || rc.holds_pressure_of >= 0)) {  // Q(p_c, λ), or λ = p_c
      const std::vector<int>& columns = coupled_columns_[b];
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(1, static_cast<Eigen::Index>(columns.size()));
      // The derivative ∂R_λ/∂x_j into the column of DOF j (λ_b's own is column 0).
      const auto add = [&](int global, double value) {
        const auto it = std::find(columns.begin(), columns.end(), global);
        FE2_CHECK(it != columns.end(), "flux ring '{}': DOF {} is not among its coupled columns", boundaries_[b].set, global);
        K(0, it - columns.begin()) += value;
      };
      if (rc.holds_pressure_of >= 0) {
        const int pc = cavity_pressure_->global_dof(rc.holds_pressure_of);
        out.add_internal({dof}, Eigen::VectorXd::Constant(1, area_[b] * (state.x[dof] - state.x[pc])));
        add(dof, area_[b]);
        add(pc, -area_[b]);
      } else {
        out.add_external({dof}, Eigen::VectorXd::Constant(1, boundaries_[b].flux(state.time)));
        for (int c = 0; c < cavity_pressure_->size() && c < static_cast<int>(rc.dQ_dp.size()); ++c)
          add(cavity_pressure_->global_dof(c), -rc.dQ_dp[static_cast<size_t>(c)]);
        for (size_t other = 0; other < rc.dQ_dring.size(); ++other)
          if (rc.dQ_dring[other] != 0.0) add(lambda_->global_dof(static_cast<int>(other)), -rc.dQ_dring[other]);
      }
      out.add_tangent(local_coupled_[b], K);
    } else if (active[b]) {
      out.add_external({dof}, Eigen::VectorXd::Constant(1, boundaries_[b].flux(state.time)));
    } else {  // a shut valve's ring: λ = 0 (its nodes stick, MovingWallTerm)
      out.add_internal({dof}, Eigen::VectorXd::Constant(1, state.x[dof]));
      out.add_tangent(local_shut_[b], Eigen::MatrixXd::Identity(1, 1));
    }
  }
}

void FluxConstraintTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  const std::vector<double> Q = face_fluxes(mesh_, *v_, d_, faces_, boundaries_.size(), state);
  for (size_t b = 0; b < boundaries_.size(); ++b) {
    out.push_back({"flux:" + boundaries_[b].set, Q[b]});
    // λ is global: one coordinator reports it, the sum over them is its value.
    out.push_back({"flux_pressure:" + boundaries_[b].set,
                   owns_globals_ ? state.x[lambda_->global_dof(static_cast<int>(b))] : 0.0});
  }
}

// --- moving walls

MovingWallTerm::MovingWallTerm(const MacroPartition& partition, std::vector<int> nodes, std::string multiplier,
                               std::shared_ptr<ValveStates> valves, std::vector<std::vector<int>> ring_of_node)
    : owns_globals_(partition.owns_globals()), nodes_(std::move(nodes)), multiplier_(std::move(multiplier)),
      valves_(std::move(valves)), ring_of_node_(std::move(ring_of_node)) {}

std::unique_ptr<MovingWallTerm> MovingWallTerm::loading_wall(const MacroPartition& partition, std::vector<int> nodes) {
  auto term = std::make_unique<MovingWallTerm>(partition, std::move(nodes));
  term->loads_wall_ = true;
  return term;
}

void MovingWallTerm::save(ByteWriter& w) const {
  if (!valves_) return;
  const std::vector<bool>& open = valves_->states();
  const std::vector<uint8_t> bytes(open.begin(), open.end());
  w.put_array(bytes.data(), bytes.size());
}

void MovingWallTerm::restore(ByteReader& r) {
  if (!valves_) return;
  const std::vector<uint8_t> bytes = r.get_array<uint8_t>();
  valves_->set_states({bytes.begin(), bytes.end()});
}

void MovingWallTerm::declare(MacroSystem& system) {
  lambda_ = &system.field(multiplier_);
  v_ = &system.field("fluid_velocity");
  d_ = system.fields().find("mesh_displacement");  // none: a fixed mesh, v̂ = 0
  if (loads_wall_) u_ = &system.field("displacement");
  if (!owns_globals_) return;
  for (size_t k = 0; k < nodes_.size(); ++k) {
    Node n;
    const int a = nodes_[k];
    for (int i = 0; i < 3; ++i) n.dofs.push_back(v_->node_dof(a, i));
    for (int i = 0; i < 3; ++i) n.dofs.push_back(lambda_->global_dof(static_cast<int>(3 * k) + i));
    if (d_ && d_->has_node(a))
      for (int i = 0; i < 3; ++i) n.dofs.push_back(d_->node_dof(a, i));
    if (u_ && u_->has_node(a))
      for (int i = 0; i < 3; ++i) n.wall.push_back(u_->node_dof(a, i));
    std::vector<int> rows(n.dofs.begin(), n.dofs.begin() + 6);
    rows.insert(rows.end(), n.wall.begin(), n.wall.end());
    n.local = system.declare_local(rows, n.dofs);
    rows_.push_back(std::move(n));
  }
}

void MovingWallTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (field.id() == lambda_->id() && owns_globals_) scale.setOnes();
}

void MovingWallTerm::assemble(const MacroState& state, MacroAssembly& out) {
  const double c0 = d_ ? state.rate(*d_).dv_dx : 0.0;  // ∂ḋ/∂d
  // Before the rings' flux rows read them (fluid_terms' order).
  if (valves_ && !valves_->updated_before_circulation()) valves_->update();
  for (size_t k = 0; k < rows_.size(); ++k) {
    const std::vector<int>& dofs = rows_[k].dofs;
    const std::vector<int>& wall = rows_[k].wall;
    const bool moving = dofs.size() == 9;
    const bool sticks = !valves_ || std::any_of(ring_of_node_[k].begin(), ring_of_node_[k].end(),
                                                [&](int ring) { return !valves_->open(ring); });
    Eigen::VectorXd R(6);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(6 + wall.size()),
                                              static_cast<Eigen::Index>(dofs.size()));
    K.block<3, 3>(0, 3).setIdentity();
    for (int i = 0; i < 3; ++i) R[i] = state.x[dofs[3 + i]];  // λ on the v row
    if (sticks) {
      for (int i = 0; i < 3; ++i) R[3 + i] = state.x[dofs[i]] - (moving ? state.v[dofs[6 + i]] : 0.0);  // v − ḋ
      K.block<3, 3>(3, 0).setIdentity();
      if (moving) K.block<3, 3>(3, 6) = -c0 * Mat3::Identity();
    } else {  // an open valve's ring: λ = 0
      for (int i = 0; i < 3; ++i) R[3 + i] = state.x[dofs[3 + i]];
      K.block<3, 3>(3, 3).setIdentity();
    }
    out.add_internal(std::vector<int>(dofs.begin(), dofs.begin() + 6), R);
    if (!wall.empty()) {  // two-way: the blood pushes the wall with λ
      out.add_external(wall, R.head<3>());
      K.block<3, 3>(6, 3) = -Mat3::Identity();
    }
    out.add_tangent(rows_[k].local, K);
  }
}

// --- the pressure level of an enclosed fluid

PressureLevelTerm::PressureLevelTerm(const TetMesh& mesh, std::vector<int> elements)
    : mesh_(mesh), elements_(std::move(elements)) {}

void PressureLevelTerm::declare(MacroSystem& system) {
  const Field& p = system.field("fluid_pressure");
  mu_ = &system.field("fluid_pressure_level");
  for (int e : elements_) {
    std::vector<int> dofs;
    for (int a : mesh_.tets[e]) dofs.push_back(p.node_dof(a));
    dofs.push_back(mu_->global_dof(0));
    dofs_.push_back(std::move(dofs));
    weights_.push_back(vertex_volumes(mesh_, e));
    local_.push_back(system.declare_local(dofs_.back()));
  }
}

void PressureLevelTerm::add_residual_scale(const Field& field, Eigen::VectorXd& scale) const {
  if (field.id() != mu_->id()) return;
  for (const Eigen::Vector4d& m : weights_) scale[0] += m.sum();
}

void PressureLevelTerm::assemble(const MacroState& state, MacroAssembly& out) {
  for (size_t k = 0; k < dofs_.size(); ++k) {
    const Eigen::VectorXd z = gather(state.x, dofs_[k]);
    Eigen::VectorXd R(5);
    R.head<4>() = z[4] * weights_[k];
    R[4] = weights_[k].dot(z.head<4>());
    out.add_internal(dofs_[k], R);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(5, 5);
    K.col(4).head<4>() = weights_[k];
    K.row(4).head<4>() = weights_[k].transpose();
    out.add_tangent(local_[k], K);
  }
}

void PressureLevelTerm::observe(const MacroState& state, std::vector<Observable>& out) const {
  // μ is global; each coordinator reports it times its share of the volume (the sum is μ V).
  double V = 0.0;
  for (const Eigen::Vector4d& m : weights_) V += m.sum();
  out.push_back({"fluid_volume_imbalance", state.x[mu_->global_dof(0)] * V});
}

}  // namespace fe2
