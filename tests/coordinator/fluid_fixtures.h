#pragma once
// A fluid scene run by the driver (macro/fluid_scene.h next to a wall), for the fluid tests.
#include "coordinator/LocalPoints.h"
#include "coordinator/Simulation.h"
#include "coordinator/macro/fluid_scene.h"

#include <gtest/gtest.h>

namespace fe2::test {

/// The Simulation of `spec` with the fluid of `setup` joined (one process).
struct FluidSimulation {
  LocalEvaluator points;
  Simulation sim;
  FluidSimulation(const RunSpec& spec, const FluidSetup& setup)
      : points(spec.models, spec.model_of_points()), sim(spec, points, fluid_extension(spec.mesh, setup)) {
    for (auto& term : fluid_terms(spec.mesh, setup, MacroPartition::whole(spec.mesh))) sim.add_term(std::move(term));
  }
  const Field& field(const std::string& name) const { return sim.system().field(name); }
  Vec3 velocity(int node) const { return sim.state().segment<3>(field("fluid_velocity").node_dof(node)); }
  double pressure(int vertex) const { return sim.state()[field("fluid_pressure").node_dof(vertex)]; }
  /// Current position of a fluid node (X + d).
  Vec3 position(const TetMesh& m, int node) const {
    const Field* d = sim.system().fields().find("mesh_displacement");
    return d ? Vec3(m.nodes[node] + sim.state().segment<3>(d->node_dof(node))) : m.nodes[node];
  }
};

/// Runs the spec `j` on one process (its fluid, if any, from the spec).
inline RunResult run_spec(const nlohmann::json& j) {
  const RunSpec spec = read_run_spec(j, "");
  LocalEvaluator points(spec.models, spec.model_of_points());
  Simulation sim(spec, points);
  return sim.run();
}

/// The observable `name` of a step (a test failure if it has none).
inline double observable(const StepRecord& h, const std::string& name) {
  for (const auto& [n, v] : h.observables)
    if (n == name) return v;
  ADD_FAILURE() << "no observable " << name;
  return 0.0;
}

}  // namespace fe2::test
