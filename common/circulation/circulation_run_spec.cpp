#include "common/circulation/circulation_run_spec.h"

#include "common/circulation/circulation_factory.h"
#include "common/circulation/circulation_keys.h"
#include "common/circulation/circulation_schema.h"

#include <cmath>

namespace fe2 {
namespace {

using namespace circulation_keys;

const char* const kTitleHelp = "one line saying what this circulation run shows";
const char* const kDescriptionHelp = "what the run shows and how to view it";
const char* const kTimeHelp =
    "how long to run: whole beats of the circulation's period, or t_end seconds";
const char* const kBeatsHelp = "number of heart beats (give beats or t_end)";
const char* const kStepsPerBeatHelp = "time steps per beat (with beats)";
const char* const kTendHelp = "end time (s) (give beats or t_end)";
const char* const kStepsHelp = "number of time steps (required with t_end)";
const Range kBeatsRange{1, 10000, false, false};
const Range kStepsRange{1, 100000000, false, false};
constexpr int kStepsPerBeat = 400;

}  // namespace

bool is_circulation_run_spec(const json& j) {
  return j.is_object() && (j.contains("ventricles") || (j.contains("circulation") && !j.contains("mesh")));
}

const SchemaNode& circulation_run_schema() {
  using namespace schema;
  static const Schema s = object(
      true, "a standalone circulation run (fe2heart circulation)",
      {{"title", string("", kTitleHelp)},
       {"description", string("", kDescriptionHelp)},
       {"circulation", [] {
          auto c = std::make_shared<SchemaNode>(*circulation_schema());
          c->required = true;
          return Schema(c);
        }()},
       {"ventricles", object(false, kVentriclesHelp,
                             {{"lv", object(false, kLvElastanceHelp, [] {
                                 SchemaKeys k;
                                 for (const auto& e : elastance_keys())
                                   k.emplace_back(e.key, number(left_ventricle().*e.member, e.range, e.help));
                                 return k;
                               }())},
                              {"rv", object(false, kRvElastanceHelp, [] {
                                 SchemaKeys k;
                                 for (const auto& e : elastance_keys())
                                   k.emplace_back(e.key, number(right_ventricle().*e.member, e.range, e.help));
                                 return k;
                               }())}})},
       {"time", exactly_one_of({"beats", "t_end"},
                               object(true, kTimeHelp,
                                      {{"beats", optional(integer(std::nullopt, kBeatsRange, kBeatsHelp))},
                                       {"steps_per_beat", integer(kStepsPerBeat, kStepsRange, kStepsPerBeatHelp)},
                                       {"t_end", optional(number(std::nullopt, Range::positive(), kTendHelp))},
                                       {"steps", optional(integer(std::nullopt, kStepsRange, kStepsHelp))}}))}});
  return *s;
}

CirculationRunSpec read_circulation_run_spec(const json& j, const std::string& file, SpecDoc* doc) {
  SpecNode root(j, "", circulation_run_schema(), doc);
  CirculationRunSpec spec;
  try {
    spec.title = root.string("title");
    root.string("description");
    SpecNode circ = root.child("circulation");
    spec.circulation = make_circulation(circ);
    const double period = spec.circulation->period();
    SpecNode ventricles = root.child("ventricles");
    for (const std::string name : {"lv", "rv"}) {
      const auto& names = spec.circulation->cavity_names();
      const bool cavity = std::find(names.begin(), names.end(), name) != names.end();
      if (!cavity && ventricles.has(name))
        ventricles.fail(name, "no " + name + " ventricle: the circulation has no " + name +
                                  " cavity (add it to circulation/cavities)");
      SpecNode v = ventricles.child(name);
      const ElastanceParameters e = read_elastance(v, period);
      v.finish();
      if (cavity) spec.ventricles.emplace_back(e, period);
    }
    ventricles.finish();
    FE2_CHECK(spec.ventricles.size() == spec.circulation->cavity_names().size(),
              "one ventricle per cavity");
    SpecNode time = root.child("time");
    if (time.has("beats") == time.has("t_end"))
      time.fail("beats", "exactly one of beats and t_end (" + std::string(kTimeHelp) + ")");
    spec.beats = time.has("beats") ? time.integer("beats") : 0;
    const int per_beat = time.integer("steps_per_beat");
    if (spec.beats) {
      spec.t_end = spec.beats * period;
      spec.steps = spec.beats * per_beat;
    } else {
      spec.t_end = time.number("t_end");
      spec.steps = time.integer("steps");
    }
    time.finish();
    root.finish();
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
  return spec;
}

}  // namespace fe2
