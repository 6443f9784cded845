#include "common/cellmodels/cell_model_factory.h"

#include "common/cellmodels/BestelClementSorine.h"
#include "common/cellmodels/Land2017.h"
#include "common/cellmodels/PrescribedTension.h"
#include "common/cellmodels/cell_model_keys.h"

#include <algorithm>
#include <cmath>

namespace fe2 {
namespace {

using namespace cell_keys;

CalciumParameters read_calcium(SpecNode& node) {
  CalciumParameters c;
  c.rest = node.number("rest");
  c.peak = node.number("peak");
  c.rise = node.number("rise");
  c.decay = node.number("decay");
  c.period = node.number("period");
  if (c.peak <= c.rest)
    node.fail("peak", fmt::format("a peak above rest = {} µM (Ca peak below rest)", c.rest));
  if (c.rise >= c.decay)
    node.fail("rise", fmt::format("a rise time below decay = {} s (tau_rise < tau_decay)", c.decay));
  node.finish();
  return c;
}

CalciumParameters read_calcium_of(SpecNode& node) {
  SpecNode calcium = node.child("calcium");
  return read_calcium(calcium);
}

double read_max_substep(SpecNode& node) {
  return node.number("max_substep");
}

CellModelPtr make_land2017(SpecNode& node) {
  const std::string set = node.choice("parameter_set");
  Land2017Parameters p = set == "skinned" ? Land2017Parameters::skinned()
                                          : Land2017Parameters::intact();
  std::string overridden;
  for (const auto& k : land_keys()) {
    if (!node.has(k.key)) continue;
    p.*k.member = node.number(k.key);
    overridden += (overridden.empty() ? "" : ", ") + std::string(k.key);
  }
  // The derived rates must stay meaningful (Land2017.h).
  if (p.k_uw * (1.0 / p.r_w - 1.0) - p.k_ws < 0.0)
    node.fail(node.has("k_ws") ? "k_ws" : "k_uw",
              fmt::format("k_ws <= k_uw (1/r_w - 1) = {} /s (the weak-to-unbound rate k_wu "
                          "would be negative)", p.k_uw * (1.0 / p.r_w - 1.0)));
  if (p.ca50_ref + 0.2 * p.beta_1 <= 0.0)
    node.fail(node.has("beta_1") ? "beta_1" : "ca50_ref",
              fmt::format("ca50_ref + 0.2 beta_1 > 0 (Ca50 at lambda = 1.2; got {} µM)",
                          p.ca50_ref + 0.2 * p.beta_1));
  const CalciumParameters calcium = read_calcium_of(node);
  const double max_substep = read_max_substep(node);
  return std::make_shared<const Land2017>(p, calcium, max_substep, set, overridden);
}

CellModelPtr make_bcs(SpecNode& node) {
  BestelClementSorineParameters p;
  p.sigma_0 = node.number("sigma_0");
  p.alpha_max = node.number("alpha_max");
  p.alpha_min = node.number("alpha_min");
  const CalciumParameters calcium = read_calcium_of(node);
  const double max_substep = read_max_substep(node);
  return std::make_shared<const BestelClementSorine>(p, calcium, max_substep);
}

CellModelPtr make_constant(SpecNode& node) {
  return std::make_shared<const ConstantTension>(
      node.number("Ta"));
}

CellModelPtr make_table(SpecNode& node) {
  const json* v = node.declared_value("table");
  const std::string expected = fmt::format("an {} ({})", kTableType, kTableHelp);
  if (!v || !v->is_array() || v->empty()) node.fail("table", expected);
  std::vector<std::pair<double, double>> table;
  for (size_t i = 0; i < v->size(); ++i) {
    const json& e = (*v)[i];
    const bool pair = e.is_array() && e.size() == 2 && e[0].is_number() && e[1].is_number() &&
                      std::isfinite(e[0].get<double>()) && std::isfinite(e[1].get<double>());
    if (!pair)
      node.fail("table", fmt::format("{}; entry {} is not a pair of numbers", expected, i));
    const double s = e[0].get<double>(), Ta = e[1].get<double>();
    if (Ta < 0.0) node.fail("table", fmt::format("{}; entry {} has T_a < 0", expected, i));
    if (!table.empty() && s <= table.back().first)
      node.fail("table", fmt::format("{}; entry {} has s = {} not above the previous {}",
                                     expected, i, s, table.back().first));
    table.emplace_back(s, Ta);
  }
  return std::make_shared<const TableTension>(std::move(table));
}

}  // namespace

std::vector<std::string> cell_model_names() { return model_names(); }

CellModelPtr make_cell_model(SpecNode& node) {
  const std::string model = node.choice("model");
  CellModelPtr m;
  if (model == Land2017::kName)
    m = make_land2017(node);
  else if (model == BestelClementSorine::kName)
    m = make_bcs(node);
  else if (model == ConstantTension::kName)
    m = make_constant(node);
  else
    m = make_table(node);
  node.finish();
  return m;
}

ActiveStressSpec read_active_stress(SpecNode& node) {
  ActiveStressSpec a;
  a.transverse_fraction = node.number("transverse_fraction");
  a.cell = make_cell_model(node);
  return a;
}

}  // namespace fe2
