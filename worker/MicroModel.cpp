#include "worker/MicroModel.h"

#include "common/error.h"
#include "common/hash.h"
#include "common/materials/material_factory.h"
#include "common/mesh/gmsh_reader.h"
#include "worker/FloatCholeskyFactor.h"
#include "worker/MumpsSingleFactor.h"
#include "worker/large_pages.h"
#include "worker/micro_cell.h"
#include "worker/micro_kernel.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <unordered_map>

namespace fe2 {


double MicroSolverOptions::step1_rtol(double relative_residual) const {
  if (gmres_forcing == Forcing::constant) return gmres_rtol;
  // Inexact Newton (Dembo, Eisenstat & Steihaug 1982): solving Step 1 to η_k ∝ ‖r_k‖
  // keeps Newton's quadratic convergence, and the coupled iteration with a kept factor is
  // only linear anyway. Far from the answer a loose solve is enough; near it η falls
  // toward gmres_rtol. The answer is fixed by the residual test, not by η.
  //
  // Kelley's safeguard (Iterative Methods for Linear and Nonlinear Equations, 1995,
  // Eq. 6.20): no solve for a residual below half the Newton tolerance, η ≥
  // 0.5·newton_rtol/(‖r‖/r_ref). The last iteration of a solve, already converged, then
  // takes the loosest η instead of gmres_rtol (1 GMRES iteration on a fresh float factor,
  // not 3): its δw₁ is applied only if another iteration follows, where a residual
  // under 0.5·newton_rtol·r_ref keeps it converged.
  const double safeguard = relative_residual > 0.0 ? 0.5 * newton_rtol / relative_residual
                                                   : std::numeric_limits<double>::infinity();
  return std::max(gmres_rtol, std::min(std::max(relative_residual, safeguard), gmres_forcing_max));
}

MicroSolverOptions MicroSolverOptions::from_spec(SpecNode s) {
  MicroSolverOptions o;
  const std::string f = s.choice("factorization");
  o.factorization = f == "cholesky" ? Factorization::cholesky
                    : f == "lu"     ? Factorization::lu
                                    : Factorization::automatic;
  const std::string r = s.choice("refresh");
  o.refresh = r == "every_iteration" ? Refresh::every_iteration
              : r == "fixed"         ? Refresh::fixed
              : r == "adaptive"      ? Refresh::adaptive
                                     : Refresh::collective;
  o.N_t = s.integer("N_t");
  o.step4 = s.boolean("step4");
  o.gmres_rtol = s.number("gmres_rtol");
  o.gmres_forcing = s.choice("gmres_forcing") == "constant"
                        ? Forcing::constant
                        : Forcing::residual;
  // A spec that loosens only gmres_rtol beyond the default keeps a consistent pair.
  const bool forcing_max_given = s.has("gmres_forcing_max");
  o.gmres_forcing_max = s.number("gmres_forcing_max");
  if (!forcing_max_given) o.gmres_forcing_max = std::max(o.gmres_forcing_max, o.gmres_rtol);
  if (o.gmres_forcing_max < o.gmres_rtol)
    s.fail("gmres_forcing_max", fmt::format("at least gmres_rtol ({:g})", o.gmres_rtol));
  o.gmres_restart = s.integer("gmres_restart");
  o.gmres_max_iterations = s.integer("gmres_max_iterations");
  o.solve_flop_cost = s.number("solve_flop_cost");
  const std::string precision = s.choice("precision");
  o.single_precision = precision != "double";
  o.half_storage = precision == "half";
  o.single_factor_mumps = s.choice("single_factor") == "mumps";
  o.blr_tolerance = s.number("blr_tolerance");
  if (o.half_storage && o.single_factor_mumps)
    s.fail("single_factor", "\"supernodal\" with \"precision\": \"half\" (MUMPS keeps its "
                            "factor in single precision)");
  if (o.blr_tolerance > 0 && !(o.single_precision && o.single_factor_mumps))
    s.fail("blr_tolerance", "0 unless \"precision\" is \"single\" and \"single_factor\" is "
                            "\"mumps\" (block low-rank is a MUMPS option)");
  s.finish();
  return o;
}

MicroModelPlan MicroModel::plan(SpecNode s, const std::string& base_dir) {
  MicroModelPlan plan;
  plan.path = s.path();
  plan.source = s.path();
  CellLayout c;
  c.kind = s.choice("cell");
  std::array<long long, 3> cells{};
  long long nodes = 0, elements = 0;
  if (c.kind == "mesh_file") {
    std::filesystem::path p = s.string("mesh_file");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    plan.file_mesh = read_gmsh_hexes(p.string());
    plan.source = p.string();
    plan.size_key = s.key_path("mesh_file");
    plan.region_names = plan.file_mesh->region_names;  // the physical volume names of the file
    // The grid with the mesh's element count and the aspect ratio of its box.
    const HexMesh& m = *plan.file_mesh;
    nodes = m.num_nodes();
    elements = m.num_hexes();
    const Vec3 L = m.hi - m.lo;
    const double h = std::cbrt(L.prod() / static_cast<double>(elements));
    for (int d = 0; d < 3; ++d) cells[d] = std::max<long long>(1, std::llround(L[d] / h));
  } else {
    const auto size = s.numbers("size");        // lengths > 0 (the schema)
    const auto res = s.numbers("resolution");   // integers in [1, 1000] (the schema)
    for (int d = 0; d < 3; ++d) {
      c.size[d] = size[d];
      c.resolution[d] = static_cast<int>(res[d]);
      cells[d] = c.resolution[d];
    }
    plan.size_key = s.key_path("resolution");
    nodes = (cells[0] + 1) * (cells[1] + 1) * (cells[2] + 1);
    elements = cells[0] * cells[1] * cells[2];
    if (c.kind == "laminate") {
      c.fraction = s.number("fraction");
      const std::string ax = s.choice("axis");
      c.axis = ax[0] - 'x';
      plan.region_names = {"a", "b"};
    } else if (c.kind == "two_cells") {
      c.gap = s.number("gap");
      c.cross_section = s.number("cross_section");
      plan.region_names = {"ecm", "cell"};
    } else {
      plan.region_names = {"matrix"};
    }
    plan.layout = c;
    const CellResolution fit = cell_resolution(c);
    if (std::abs(fit.realised - fit.nominal) > 0.1 * fit.nominal)
      spdlog::warn("{} [{}, {}, {}] does not resolve the {} layout: its elements give {} {:.1f} % of "
                   "the unit's volume, the layout {:.1f} %{}. Interfaces move to element faces, so "
                   "refining changes the microstructure too; resolutions that are multiples of "
                   "[{}, {}, {}] (0: none up to 1000) put every interface on element faces",
                   plan.size_key, c.resolution[0], c.resolution[1], c.resolution[2], c.kind,
                   c.kind == "two_cells" ? "the cells" : "phase b", 100.0 * fit.realised,
                   100.0 * fit.nominal,
                   c.kind == "two_cells" ? fmt::format(" (gap {}, cross_section {})", c.gap, c.cross_section)
                                         : fmt::format(" (fraction {})", c.fraction),
                   fit.exact[0], fit.exact[1], fit.exact[2]);
  }
  SpecNode mats = s.child("materials");
  for (const auto& name : plan.region_names) {
    SpecNode m = mats.child(name);
    plan.materials.push_back(make_material(m));
  }
  mats.finish();
  plan.options = MicroSolverOptions::from_spec(s.child("solver"));
  s.finish();
  bool symmetric = true;
  for (const auto& m : plan.materials) symmetric = symmetric && m->major_symmetric();
  const bool lu = plan.options.factorization == MicroSolverOptions::Factorization::lu ||
                  (plan.options.factorization == MicroSolverOptions::Factorization::automatic &&
                   !symmetric);
  plan.memory = estimate_micro_memory(cells, nodes, elements, lu, plan.options.single_precision,
                                      plan.options.half_storage);
  return plan;
}

bool MicroModelPlan::may_run_mumps() const {
  return options.single_precision &&
         (options.single_factor_mumps || options.factorization != MicroSolverOptions::Factorization::cholesky);
}

int MicroModelPlan::check() const {
  const HexMesh mesh = file_mesh ? *file_mesh : make_cell_mesh(*layout);
  const PeriodicDofMap dofs(mesh, source);
  for (size_t e = 0; e < mesh.region.size(); ++e)
    if (mesh.region[e] < 0 || mesh.region[e] >= static_cast<int>(materials.size()))
      throw InputError(fmt::format("micro mesh '{}': element {} has region {} but only {} "
                                   "materials are given",
                                   source, e, mesh.region[e], materials.size()));
  return dofs.num_dofs();
}

std::shared_ptr<const MicroModel> MicroModelPlan::build() const {
  return std::make_shared<const MicroModel>(file_mesh ? *file_mesh : make_cell_mesh(*layout),
                                            materials, options, source);
}

std::shared_ptr<const MicroModel> MicroModel::from_spec(SpecNode s, const std::string& base_dir) {
  return plan(std::move(s), base_dir).build();
}

MicroModel::MicroModel(HexMesh mesh, std::vector<MaterialPtr> materials,
                       MicroSolverOptions options, const std::string& source)
    : mesh_(std::move(mesh)),
      materials_(std::move(materials)),
      options_(options),
      dofs_(mesh_, source) {
  const int ne = mesh_.num_hexes();
  FE2_CHECK(static_cast<int>(mesh_.region.size()) == ne, "region per hex");
  for (int e = 0; e < ne; ++e)
    if (mesh_.region[e] < 0 || mesh_.region[e] >= static_cast<int>(materials_.size()))
      throw InputError(fmt::format("micro mesh '{}': element {} has region {} but only {} "
                                   "materials are given",
                                   source, e, mesh_.region[e], materials_.size()));
  double floor = 0.0;
  for (const auto& m : materials_) {
    symmetric_ = symmetric_ && m->major_symmetric();
    floor = std::max(floor, 1e-6 * m->stiffness_scale());
  }
  stress_floor_ = floor;

  // Point contexts and history: offsets only when some law keeps history.
  bool any_history = false;
  for (const auto& m : materials_) {
    uses_context_.push_back(m->uses_context() ? 1 : 0);
    any_history = any_history || m->history_size() > 0;
  }
  if (any_history) {
    history_offset_.assign(static_cast<size_t>(ne) + 1, 0);
    for (int e = 0; e < ne; ++e)
      history_offset_[e + 1] = history_offset_[e] + 8 * static_cast<size_t>(material_of(e).history_size());
  }

  geometry_of_.resize(ne);
  eq_.resize(ne);
  std::vector<double> rho(mesh_.num_nodes(), 0.0);  // ⟨|∇N_a|⟩ on masters
  std::unordered_multimap<uint64_t, int> geometry_by_hash;
  for (int e = 0; e < ne; ++e) {
    const HexGeometry geo = hex_geometry(mesh_, e);
    Fnv1a hash;
    hash.add(&geo, sizeof(geo));
    const auto [first, last] = geometry_by_hash.equal_range(hash.value());
    const auto same = std::find_if(first, last, [&](const auto& entry) {
      return std::memcmp(&geometry_[entry.second], &geo, sizeof(geo)) == 0;
    });
    if (same != last) {
      geometry_of_[e] = same->second;
    } else {
      geometry_of_[e] = static_cast<int>(geometry_.size());
      geometry_by_hash.emplace(hash.value(), geometry_of_[e]);
      geometry_.push_back(geo);
    }
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 8; ++a) eq_[e][8 * i + a] = dofs_.dof(mesh_.hexes[e][a], i);
    for (int q = 0; q < 8; ++q)
      for (int a = 0; a < 8; ++a)
        rho[dofs_.master(mesh_.hexes[e][a])] +=
            geo.weight[q] * geo.grad[q].col(a).norm() / mesh_.volume();
  }
  double s2 = 0.0;
  for (double v : rho) s2 += v * v;
  node_scale_ = std::sqrt(s2);

  // Fixed pattern of K: one nonzero per pair of equations sharing an element.
  const int n = dofs_.num_dofs();
  std::vector<std::vector<int>> rows(n);
  for (int e = 0; e < ne; ++e)
    for (int l : eq_[e])
      if (l >= 0)
        for (int m : eq_[e])
          if (m >= 0) rows[m].push_back(l);  // column m holds row l
  std::vector<Eigen::Triplet<double>> trip;
  for (int col = 0; col < n; ++col) {
    auto& r = rows[col];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    for (int row : r) trip.emplace_back(row, col, 0.0);
  }
  pattern_.resize(n, n);
  pattern_.setFromTriplets(trip.begin(), trip.end());
  pattern_.makeCompressed();
  scatter_.resize(ne);
  const int* outer = pattern_.outerIndexPtr();
  const int* inner = pattern_.innerIndexPtr();
  const auto position = [&](int row, int col) {
    const int* pos = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
    FE2_CHECK(pos != inner + outer[col + 1] && *pos == row, "pattern holds every element entry");
    return static_cast<int>(pos - inner);
  };
  for (int e = 0; e < ne; ++e) {
    ElementScatter& sc = scatter_[e];
    for (int b = 0; b < 8; ++b) {
      const int col = eq_[e][hex_local(0, b)];
      sc.stride[b] = col >= 0 ? outer[col + 1] - outer[col] : 0;
      for (int a = 0; a < 8; ++a) {
        const int row = eq_[e][hex_local(0, a)];
        int& p = sc.block[8 * a + b];
        p = row >= 0 && col >= 0 ? position(row, col) : -1;
        // The layout the assembly relies on, checked entry by entry once per model.
        for (int k = 0; k < 3 && p >= 0; ++k)
          for (int i = 0; i < 3; ++i)
            FE2_CHECK(position(eq_[e][hex_local(i, a)], eq_[e][hex_local(k, b)]) == p + i + k * sc.stride[b],
                      "a node's rows adjacent and its columns alike in K's pattern");
      }
    }
  }

  // Fingerprint: sizes, regions and options (cheap FNV-1a over the defining data).
  Fnv1a hash;
  auto mix = [&hash](const void* p, size_t len) { hash.add(p, len); };
  mix(&n, sizeof n);
  mix(mesh_.region.data(), mesh_.region.size() * sizeof(int));
  for (const auto& X : mesh_.nodes) mix(X.data(), 3 * sizeof(double));
  for (const auto& m : materials_) {
    const std::string nm = m->name();
    mix(nm.data(), nm.size());
    const double s = m->stiffness_scale();
    mix(&s, sizeof s);
  }
  fingerprint_ = hash.value();
}

void MicroModel::initial_history(std::span<double> history) const {
  if (history_offset_.empty()) return;
  for (int e = 0; e < num_elements(); ++e) {
    const Material& m = material_of(e);
    const size_t h = static_cast<size_t>(m.history_size());
    for (size_t q = 0; q < 8 && h > 0; ++q) m.initial_history(history.subspan(history_offset_[e] + q * h, h));
  }
}

SparseMatrix MicroModel::zero_matrix() const {
  const int n = static_cast<int>(pattern_.rows());
  const Eigen::Index nnz = pattern_.nonZeros();
  SparseMatrix K(n, n);
  K.resizeNonZeros(nnz);  // allocated, not yet filled: the advice still applies
  advise_large_pages(K.valuePtr(), static_cast<size_t>(nnz) * sizeof(double));
  std::copy_n(pattern_.outerIndexPtr(), n + 1, K.outerIndexPtr());
  std::copy_n(pattern_.innerIndexPtr(), nnz, K.innerIndexPtr());
  std::fill_n(K.valuePtr(), nnz, 0.0);
  return K;
}

FactorKind MicroModel::initial_factor_kind() const {
  switch (options_.factorization) {
    case MicroSolverOptions::Factorization::cholesky: return FactorKind::cholesky;
    case MicroSolverOptions::Factorization::lu: return FactorKind::lu;
    default: return symmetric_ ? FactorKind::cholesky : FactorKind::lu;
  }
}

std::unique_ptr<SparseFactor> MicroModel::make_factor(FactorKind kind) const {
  if (options_.single_precision && kind == FactorKind::cholesky && !options_.single_factor_mumps)
    return make_float_cholesky_factor(options_.half_storage);
  if (options_.single_precision)
    return make_mumps_single_factor(kind == FactorKind::cholesky, options_.blr_tolerance);
  return make_sparse_factor(kind);
}

}  // namespace fe2
