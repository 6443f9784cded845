// Checks on the output folders of task-farm runs, for the mpi tests:
//   farm_check compare REF OUT TOL [MIN_MIGRATIONS]   probe positions agree to TOL times the
//                                                     largest probe displacement (0: bit for bit),
//                                                     each step's observables to TOL times the
//                                                     largest |value| of each
//   farm_check imbalance DIR below|above X            imbalance after the first rebalance
//   farm_check at_least DIR POINTER MIN               summary.json's number at a JSON pointer
//                                                     (e.g. /factor_memory/evictions) >= MIN
//   farm_check trace DIR KEY MIN MAX                  every line of trace_iterations.jsonl has
//                                                     MIN <= KEY <= MAX (e.g. macro_law_jobs_sent 0 0)
// Prints what it compared; exits 1 on a failed check, 2 on unreadable input.
#include "coordinator/farm/trace_analysis.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

using nlohmann::json;

namespace {

json read(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    std::cerr << "cannot open " << path << "\n";
    std::exit(2);
  }
  return json::parse(in);
}

/// Largest relative difference over every number in the probes and residual histories.
double compare(const json& a, const json& b, const std::string& where, double scale, bool& same_shape) {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    return std::abs(x - y) / std::max(scale, 1e-300);
  }
  if (a.type() != b.type() || a.size() != b.size()) {
    std::cerr << "shape differs at " << where << "\n";
    same_shape = false;
    return INFINITY;
  }
  double d = 0.0;
  if (a.is_object())
    for (auto it = a.begin(); it != a.end(); ++it)
      if (it.key() != "wall_seconds")  // differs from run to run; not a result
      d = std::max(d, compare(it.value(), b.at(it.key()), where + "/" + it.key(), scale, same_shape));
  if (a.is_array())
    for (size_t i = 0; i < a.size(); ++i)
      d = std::max(d, compare(a[i], b[i], where + "/" + std::to_string(i), scale, same_shape));
  return d;
}

/// Largest probe displacement component, |x − X|, with X from the run's spec.json: the
/// tolerance is relative to how far the probes moved, not to where they are.
double displacement_scale(const json& summary, const json& spec, const std::string& dir) {
  double m = 0.0;
  for (auto it = summary["probes"].begin(); it != summary["probes"].end(); ++it) {
    if (!spec["probes"].contains(it.key())) {
      std::cerr << dir << "/spec.json has no probe '" << it.key() << "'\n";
      std::exit(2);
    }
    const json& X = spec["probes"][it.key()];
    for (size_t i = 0; i < 3; ++i)
      m = std::max(m, std::abs(it.value()[i].get<double>() - X[i].get<double>()));
  }
  if (!(m > 0.0)) {
    std::cerr << dir << ": the probes did not move; a relative comparison needs a displacement\n";
    std::exit(2);
  }
  return m;
}
/// Every step's observables (history[].observables: fluid fluxes, energies, ...): the
/// largest difference relative to the largest |value| over the reference's steps of the
/// names of its kind (the part before ':', e.g. every flux:<set>), so that a shut ring's
/// flux, zero to round-off, is measured against the flow the others pass. −1 when the
/// runs have none.
double compare_observables(const json& ref, const json& out, bool& same_shape) {
  const json &a = ref["history"], &b = out["history"];
  if (a.empty() || !a[0].contains("observables")) return -1.0;
  if (a.size() != b.size()) {
    same_shape = false;
    return INFINITY;
  }
  double d = 0.0;
  const auto kind = [](const std::string& name) { return name.substr(0, name.find(':')); };
  for (auto it = a[0]["observables"].begin(); it != a[0]["observables"].end(); ++it) {
    double scale = 0.0;
    for (const json& h : a)
      for (auto o = h["observables"].begin(); o != h["observables"].end(); ++o)
        if (kind(o.key()) == kind(it.key())) scale = std::max(scale, std::abs(o.value().get<double>()));
    for (size_t s = 0; s < a.size(); ++s) {
      if (!b[s].contains("observables") || !b[s]["observables"].contains(it.key())) {
        std::cerr << "history/" << s << " lacks observable " << it.key() << "\n";
        same_shape = false;
        return INFINITY;
      }
      d = std::max(d, compare(a[s]["observables"][it.key()], b[s]["observables"][it.key()],
                              "history/" + std::to_string(s) + "/observables/" + it.key(), scale, same_shape));
    }
  }
  return d;
}

/// A coupled run's pressure–volume loop: the largest difference over the steps of every
/// cavity volume and circulation pressure, relative to the largest volume (pressure) of
/// the reference. −1 when the runs have no cavities.
double compare_pv_loop(const json& ref, const json& out, bool& same_shape) {
  const json &a = ref["history"], &b = out["history"];
  if (a.empty() || !a[0].contains("cavity_volumes")) return -1.0;
  if (a.size() != b.size()) {
    std::cerr << "the runs have " << a.size() << " and " << b.size() << " steps\n";
    same_shape = false;
    return INFINITY;
  }
  double d = 0.0;
  for (const char* key : {"cavity_volumes", "compartment_pressures"}) {
    double scale = 0.0;
    for (const json& h : a)
      if (h.contains(key))
        for (const auto& v : h[key]) scale = std::max(scale, std::abs(v.get<double>()));
    for (size_t s = 0; s < a.size(); ++s)
      if (a[s].contains(key))
        d = std::max(d, compare(a[s][key], b[s].value(key, json()), std::string("history/") + std::to_string(s) + "/" + key,
                                scale, same_shape));
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "compare" && argc >= 5) {
    const json ref = read(std::string(argv[2]) + "/summary.json");
    const json out = read(std::string(argv[3]) + "/summary.json");
    const double tol = std::stod(argv[4]);
    const int min_migrations = argc > 5 ? std::stoi(argv[5]) : 0;
    bool ok = ref["converged"].get<bool>() && out["converged"].get<bool>();
    bool shape = true;
    // A scene without probes (a fluid alone) is compared by its observables.
    const bool probes = ref.contains("probes") && !ref["probes"].empty();
    const double scale = probes ? displacement_scale(ref, read(std::string(argv[2]) + "/spec.json"), argv[2]) : 1.0;
    const double d_probes = probes ? compare(ref["probes"], out["probes"], "probes", scale, shape) : 0.0;
    const bool same_iterations = ref["newton_iterations"] == out["newton_iterations"];
    const fe2::TraceSummary t = fe2::summarize(fe2::read_traces(argv[3]));
    std::printf("probes: max difference %.3e of the largest probe displacement %.3e (tolerance "
                "%.1e); Newton iterations %d vs %d; migrations %d (at least %d)\n",
                d_probes, scale, tol, ref["newton_iterations"].get<int>(), out["newton_iterations"].get<int>(),
                t.migrations, min_migrations);
    if (tol == 0.0) {  // bit for bit: every number of the residual histories too
      const double d_hist = compare(ref["history"], out["history"], "history", 1.0, shape);
      std::printf("history (residuals, iterations): %s\n", d_hist == 0.0 ? "identical" : "differs");
      ok = ok && d_hist == 0.0;
    }
    const double d_pv = compare_pv_loop(ref, out, shape);
    if (d_pv >= 0)
      std::printf("pressure-volume loop: max difference %.3e of the largest volume / pressure (tolerance %.1e)\n",
                  d_pv, tol);
    const double d_obs = compare_observables(ref, out, shape);
    if (d_obs >= 0)
      std::printf("observables: max difference %.3e of each one's largest |value| (tolerance %.1e)\n", d_obs, tol);
    if (!probes && d_obs < 0) {
      std::cerr << "the runs have neither probes nor observables to compare\n";
      return 2;
    }
    ok = ok && shape && d_probes <= tol && d_pv <= tol && d_obs <= tol && same_iterations &&
         t.migrations >= min_migrations;
    std::printf("%s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
  }
  if (mode == "imbalance" && argc == 5) {
    const fe2::TraceSummary t = fe2::summarize(fe2::read_traces(argv[2]));
    const std::string dir = argv[3];
    const double x = std::stod(argv[4]);
    const double v = t.imbalance_after_first_rebalance;
    std::printf("imbalance (max/mean worker busy) after the first rebalance: %.3f (mean %.3f, "
                "max %.3f, migrations %d); expected %s %.2f\n",
                v, t.imbalance_mean, t.imbalance_max, t.migrations, dir.c_str(), x);
    const bool ok = dir == "below" ? v < x : v > x;
    std::printf("%s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
  }
  if (mode == "at_least" && argc == 5) {
    const json summary = read(std::string(argv[2]) + "/summary.json");
    const json::json_pointer at(argv[3]);
    if (!summary.contains(at) || !summary[at].is_number()) {
      std::cerr << argv[2] << "/summary.json has no number at " << argv[3] << "\n";
      return 2;
    }
    const double v = summary[at].get<double>(), min = std::stod(argv[4]);
    std::printf("%s: %g (at least %g)\n%s\n", argv[3], v, min, v >= min ? "PASS" : "FAIL");
    return v >= min ? 0 : 1;
  }
  if (mode == "trace" && argc == 6) {
    const fe2::TraceData t = fe2::read_traces(argv[2]);
    const std::string key = argv[3];
    const double lo = std::stod(argv[4]), hi = std::stod(argv[5]);
    double low = INFINITY, high = -INFINITY, total = 0;
    for (const json& it : t.iterations) {
      if (!it.contains(key) || !it[key].is_number()) {
        std::cerr << argv[2] << "/trace_iterations.jsonl: a line has no number '" << key << "'\n";
        return 2;
      }
      const double v = it[key].get<double>();
      low = std::min(low, v), high = std::max(high, v), total += v;
    }
    const bool ok = low >= lo && high <= hi;
    std::printf("%s over %zu iterations: min %g, max %g, total %g (expected each in [%g, %g])\n%s\n",
                key.c_str(), t.iterations.size(), low, high, total, lo, hi, ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
  }
  std::cerr << "usage: farm_check compare REF OUT TOL [MIN_MIGRATIONS] | imbalance DIR below|above X | "
               "at_least DIR POINTER MIN | trace DIR KEY MIN MAX\n";
  return 2;
}
