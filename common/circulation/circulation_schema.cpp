// The <circulation> schema: the same keys, defaults, ranges and help texts that
// make_circulation reads (both loop over the tables of circulation_keys.h).
#include "common/circulation/circulation_schema.h"

#include "common/circulation/circulation_keys.h"

namespace fe2 {
namespace {

using namespace schema;
using namespace circulation_keys;

template <class P>
SchemaKeys keys_of(const P& def, const std::vector<Key<P>>& keys) {
  SchemaKeys out;
  for (const auto& k : keys) out.emplace_back(k.key, number(def.*k.member, k.range, k.help));
  return out;
}

Schema valve(const char* help) { return object(false, help, keys_of(default_valve(), valve_keys())); }

Schema preload(bool left) {
  const PreloadParameters d = left ? lv_preload() : rv_preload();
  SchemaKeys atrium = keys_of(left ? left_atrium() : right_atrium(), elastance_keys());
  for (auto& k : keys_of(d, atrium_feed_keys())) atrium.push_back(k);
  return object(false, kPreloadHelp,
                {{"kind", choice(preload_kinds()[0], preload_kinds(), kPreloadKindHelp)}}, "kind",
                {{"pressure",
                  {{kPreloadPressure.key,
                    number(d.*kPreloadPressure.member, kPreloadPressure.range, kPreloadPressure.help)}}},
                 {"atrium", atrium}});
}

Schema windkessel_cavity(bool left) {
  return object(left, left ? kLvHelp : kRvHelp,
                {{"preload", preload(left)},
                 {"inflow_valve", valve(kInflowValveHelp)},
                 {"outflow_valve", valve(kOutflowValveHelp)},
                 {"windkessel", object(false, kWindkesselHelp,
                                       keys_of(left ? lv_windkessel() : rv_windkessel(), windkessel_keys()))}});
}

Schema loop_cavity(bool left) {
  return object(left, kLoopCavityHelp,
                {{"inflow_valve", valve(kInflowValveHelp)}, {"outflow_valve", valve(kOutflowValveHelp)}});
}

Schema elastance(const ElastanceParameters& def, const char* help) {
  return object(false, help, keys_of(def, elastance_keys()));
}

}  // namespace

Schema circulation_schema() {
  static const Schema s = defined(
      "circulation",
      object(false, kCirculationHelp,
             {{"kind", choice(kinds()[0], kinds(), kKindHelp)},
              {"period", number(kPeriod, Range::positive(), kPeriodHelp)}},
             "kind",
             {{"windkessel",
               {{"cavities", object(true, kCavitiesHelp,
                                    {{"lv", windkessel_cavity(true)}, {"rv", windkessel_cavity(false)}})}}},
              {"closed_loop",
               {{"cavities", object(true, kCavitiesHelp, {{"lv", loop_cavity(true)}, {"rv", loop_cavity(false)}})},
                {"systemic", object(false, kSystemicHelp, keys_of(systemic(), vessel_keys()))},
                {"pulmonary", object(false, kPulmonaryHelp, keys_of(pulmonary(), vessel_keys()))},
                {"left_atrium", elastance(left_atrium(), kLeftAtriumHelp)},
                {"right_atrium", elastance(right_atrium(), kRightAtriumHelp)},
                {"right_ventricle", elastance(right_ventricle(), kInternalRvHelp)}}}}));
  return s;
}

}  // namespace fe2
