// The <cell_model> schema: the same keys, defaults, ranges and help texts that
// make_cell_model reads (both take them from cell_model_keys.h).
#include "common/cellmodels/cell_model_schema.h"

#include "common/cellmodels/cell_model_keys.h"

namespace fe2 {
namespace {

using namespace schema;
using namespace cell_keys;
using std::nullopt;

/// Fresh nodes per branch, so a coverage test sees each branch's keys read.
Schema calcium() {
  const CalciumParameters d;
  const Range pos = Range::positive();
  return object(false, kCalciumHelp,
                {{"rest", number(d.rest, pos, kRestHelp)},
                 {"peak", number(d.peak, pos, kPeakHelp)},
                 {"rise", number(d.rise, pos, kRiseHelp)},
                 {"decay", number(d.decay, pos, kDecayHelp)},
                 {"period", number(d.period, Range::non_negative(), kPeriodHelp)}});
}

Schema max_substep() { return number(kMaxSubstep, Range::positive(), kMaxSubstepHelp); }

SchemaKeys land2017_keys() {
  SchemaKeys k = {{"parameter_set", choice(parameter_sets()[0], parameter_sets(), kParameterSetHelp)}};
  for (const auto& p : land_keys())
    k.emplace_back(p.key, optional(number(nullopt, p.range, land_help(p))));
  k.emplace_back("calcium", calcium());
  k.emplace_back("max_substep", max_substep());
  return k;
}

SchemaKeys bcs_keys() {
  const BestelClementSorineParameters d;
  return {{"sigma_0", number(d.sigma_0, Range::positive(), kSigma0Help)},
          {"alpha_max", number(d.alpha_max, Range::positive(), kAlphaMaxHelp)},
          {"alpha_min", number(d.alpha_min, kNegative, kAlphaMinHelp)},
          {"calcium", calcium()},
          {"max_substep", max_substep()}};
}

SchemaKeys table_keys() {
  const json pair = {{"type", "array"},
                     {"prefixItems", json::array({{{"type", "number"}},
                                                  {{"type", "number"}, {"minimum", 0}}})},
                     {"minItems", 2},
                     {"maxItems", 2}};
  const json table = {{"type", "array"}, {"minItems", 1}, {"items", pair}};
  return {{"table", required(custom(kTableType, kTableHelp, table))}};
}

}  // namespace

Schema cell_model_schema() {
  static const Schema s = defined(
      "cell_model",
      object(false, kModelHelp,
             {{"model", choice(nullopt, model_names(), kModelHelp)},
              {"transverse_fraction", number(0.0, Range{0.0, 1.0, false, true}, kTransverseHelp)}},
             "model",
             {{Land2017::kName, land2017_keys()},
              {BestelClementSorine::kName, bcs_keys()},
              {"constant", {{"Ta", number(nullopt, Range::non_negative(), kTaHelp)}}},
              {"table", table_keys()}}));
  return s;
}

}  // namespace fe2
