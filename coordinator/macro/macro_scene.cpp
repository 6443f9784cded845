#include "coordinator/macro/macro_scene.h"

#include "coordinator/macro/CavityPressureTerm.h"
#include "coordinator/macro/FollowerPressureTerm.h"
#include "coordinator/macro/IncompressibilityTerm.h"
#include "coordinator/macro/InertiaTerm.h"
#include "coordinator/macro/fluid_scene.h"

namespace fe2 {

MacroExtension scene_extension(const RunSpec& spec, const MacroExtension& extension) {
  if (!spec.fluid) return extension;
  MacroExtension ext = fluid_extension(spec.mesh, *spec.fluid);
  for (FieldDecl& f : ext.fields) f.rtol = spec.rtol_of(f.name);  // newton.field_rtol per fluid field
  for (const FieldDecl& f : extension.fields) ext.fields.push_back(f);
  if (extension.constrain)
    ext.constrain = [fluid = ext.constrain, more = extension.constrain](const FieldTable& t, MacroConstraints& c) {
      fluid(t, c);
      more(t, c);
    };
  if (extension.initial) {
    auto fluid = ext.initial;
    ext.initial = [fluid, more = extension.initial](const FieldTable& t, Eigen::VectorXd& x, Eigen::VectorXd& v) {
      if (fluid) fluid(t, x, v);
      more(t, x, v);
    };
  }
  return ext;
}

FieldTable scene_fields(const RunSpec& spec, const MacroExtension& user_extension) {
  const MacroExtension extension = scene_extension(spec, user_extension);
  FieldTable t;
  FieldDecl u;
  u.name = "displacement";
  u.components = 3;
  u.space = FieldSpace::nodal;
  u.regions = spec.wall_regions;
  // Quasi-static: no rate; the point models difference Z̄ over the step themselves.
  u.time = spec.dynamic ? TimeScheme::newmark : TimeScheme::none;
  u.norm = ResidualNorm::relative_to_load;
  u.rtol = spec.rtol_of(u.name);
  t.add(u);
  if (spec.formulation.mixed) {
    FieldDecl p;
    p.name = "pressure";
    p.space = spec.formulation.element_pressure ? FieldSpace::vertex_element : FieldSpace::vertex;
    p.regions = spec.wall_regions;
    // R_p relative to ∫N_p: the volumetric strain J̄ − 1 (+ p/κ) not yet removed.
    p.norm = ResidualNorm::scaled_l2;
    p.rtol = spec.rtol_of(p.name);
    t.add(p);
  }
  if (spec.circulation) {
    FieldDecl pc;
    pc.name = "cavity_pressure";
    pc.space = FieldSpace::global;
    pc.count = static_cast<int>(spec.coupled_cavities.size());
    // R_c relative to the cavity's unloaded volume, the worst cavity.
    pc.norm = ResidualNorm::scaled_max;
    pc.rtol = spec.rtol_of(pc.name);
    t.add(pc);
  }
  for (const FieldDecl& f : extension.fields) t.add(f);
  t.number(spec.mesh);
  return t;
}

MacroSystem make_macro_system(const RunSpec& spec, const MacroExtension& user_extension) {
  const MacroExtension extension = scene_extension(spec, user_extension);
  FieldTable fields = scene_fields(spec, user_extension);
  MacroConstraints constraints;
  const Field& u = fields.at("displacement");
  for (size_t d = 0; d < spec.dirichlet.size(); ++d) {
    const DirichletSpec& ds = spec.dirichlet[d];
    for (int i = 0; i < 3; ++i) {
      if (!ds.fixed[i]) continue;
      const int source = constraints.add_value(
          [&spec, d, i](double t) { return spec.dirichlet[d].value[i] * ramp_factor(spec.dirichlet[d].ramp, t, spec.t_end); });
      // A set may reach past the wall (a base plane through wall and cavity): its wall nodes.
      for (int node : spec.mesh.node_sets.at(ds.set))
        if (u.has_node(node)) constraints.prescribe(u.node_dof(node, i), source);
    }
  }
  if (extension.constrain) extension.constrain(fields, constraints);
  return MacroSystem(spec.mesh, std::move(fields), std::move(constraints));
}

std::vector<std::unique_ptr<MacroTerm>> scene_terms(const RunSpec& spec, const MacroPoints& points,
                                                    const MacroPartition& partition,
                                                    const std::vector<PointResponse>& responses) {
  const std::vector<int> wall = spec.wall_elements_among(partition.elements());
  std::vector<std::unique_ptr<MacroTerm>> terms;
  terms.push_back(std::make_unique<PointStressTerm>(spec.mesh, points, wall, responses));
  if (spec.dynamic) terms.push_back(std::make_unique<InertiaTerm>(spec.mesh, wall, spec.density));
  if (!spec.pressure.empty()) terms.push_back(std::make_unique<FollowerPressureTerm>(spec, partition));
  CavityPressureTerm* cavities = nullptr;
  if (spec.circulation) {
    auto term = std::make_unique<CavityPressureTerm>(spec, partition);
    cavities = term.get();
    terms.push_back(std::move(term));
  }
  if (spec.formulation.mixed)
    terms.push_back(std::make_unique<IncompressibilityTerm>(spec.mesh, points, wall, spec.formulation));
  if (spec.fluid)
    for (auto& term : fluid_terms(spec.mesh, *spec.fluid, partition, cavities)) terms.push_back(std::move(term));
  return terms;
}

}  // namespace fe2
