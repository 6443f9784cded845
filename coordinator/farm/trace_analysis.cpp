#include "coordinator/farm/trace_analysis.h"

#include "common/error.h"
#include "common/median.h"

#include <algorithm>
#include <fstream>
#include <map>

namespace fe2 {

namespace {

std::vector<nlohmann::json> read_lines(const std::string& path, bool required) {
  std::ifstream in(path);
  if (!in) {
    if (required)
      throw InputError(fmt::format("cannot open trace file '{}': expected the output folder of "
                                   "`fe2heart run`",
                                   path));
    return {};
  }
  std::vector<nlohmann::json> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (line.empty()) continue;
    try {
      out.push_back(nlohmann::json::parse(line));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("trace file '{}' line {} is not JSON: {}", path, n, e.what()));
    }
  }
  return out;
}

double median(std::vector<double> v) { return fe2::median(std::move(v), 0.0); }

}  // namespace

MacroSolveKind macro_solve_kind(const nlohmann::json& it) {
  if (!it.contains("macro_factorized")) return MacroSolveKind::unknown;
  if (it.at("macro_factorized").get<int>() > 0) return MacroSolveKind::factorizing;
  return it.at("solve").get<double>() > 0 ? MacroSolveKind::kept : MacroSolveKind::none;
}

double MacroCost::predict(MacroSolveKind k) const {
  const Kind* kind = k == MacroSolveKind::factorizing ? &factorizing
                     : k == MacroSolveKind::kept     ? &kept
                     : k == MacroSolveKind::none     ? &none
                                                     : nullptr;
  return kind && kind->count > 0 ? kind->cpu : solving_median;
}

MacroCost macro_cost(const TraceData& t) {
  MacroCost c;
  struct Samples {
    std::vector<double> wall, cpu, assemble, solve, gmres;
  } f, k, n;
  std::vector<double> solving;
  for (const auto& it : t.iterations) {
    const double wall = it.at("macro").get<double>();
    c.macro_wall += wall;
    c.fluid_assembly += it.value("assemble_fluid", 0.0);
    c.cpu_recorded = it.contains("macro_cpu_max");
    const double cpu = it.value("macro_cpu_max", wall);
    c.cpu_critical += cpu;
    c.cpu_total += it.value("macro_cpu_sum", wall);
    c.coordinators = std::max(c.coordinators, it.value("coordinators", 1));
    const MacroSolveKind kind = macro_solve_kind(it);
    if (kind == MacroSolveKind::unknown) {  // an older trace: no kinds, one median
      solving.push_back(cpu);
      continue;
    }
    Samples& s = kind == MacroSolveKind::factorizing ? f : kind == MacroSolveKind::none ? n : k;
    s.wall.push_back(wall);
    s.cpu.push_back(cpu);
    s.assemble.push_back(it.at("assemble").get<double>());
    s.solve.push_back(it.at("solve").get<double>());
    s.gmres.push_back(it.value("macro_gmres", 0));
    if (kind != MacroSolveKind::none) solving.push_back(cpu);
  }
  const auto fill = [](MacroCost::Kind& kind, const Samples& s) {
    kind.count = static_cast<int>(s.wall.size());
    kind.wall = median(s.wall);
    kind.cpu = median(s.cpu);
    kind.assemble = median(s.assemble);
    kind.solve = median(s.solve);
    kind.gmres = median(s.gmres);
  };
  fill(c.factorizing, f);
  fill(c.kept, k);
  fill(c.none, n);
  c.solving_median = median(solving);
  return c;
}

TraceData read_traces(const std::string& dir) {
  TraceData t;
  t.iterations = read_lines(dir + "/trace_iterations.jsonl", true);
  t.workers = read_lines(dir + "/trace_workers.jsonl", true);
  t.units = read_lines(dir + "/trace_units.jsonl", false);
  if (t.iterations.empty())
    throw InputError(fmt::format("'{}/trace_iterations.jsonl' has no iterations: the run "
                                 "stopped before its first Newton iteration",
                                 dir));
  return t;
}

TraceSummary summarize(const TraceData& t) {
  TraceSummary s;
  s.iterations = static_cast<int>(t.iterations.size());
  long long bytes = 0, jobs = 0;
  for (size_t i = 0; i < t.iterations.size(); ++i) {
    const auto& it = t.iterations[i];
    s.entire += it.at("entire").get<double>();
    s.micro_lc += it.at("micro_lc").get<double>();
    s.macro += it.at("macro").get<double>();
    s.comm1 += it.at("comm1").get<double>();
    s.comm2 += it.at("comm2").get<double>();
    bytes += it.at("bytes").get<long long>();
    jobs += it.at("jobs").get<long long>();
    const int m = it.at("migrations").get<int>();
    s.migrations += m;
    if (m > 0 && s.first_rebalance_iteration < 0) s.first_rebalance_iteration = static_cast<int>(i);
  }
  s.micro_over_entire = s.entire > 0 ? s.micro_lc / s.entire : 0;
  s.macro_over_entire = s.entire > 0 ? s.macro / s.entire : 0;
  s.bytes_per_unit_iteration = jobs > 0 ? static_cast<double>(bytes) / jobs : 0;

  // Worker busy time per (step, iteration), in trace order.
  std::map<std::pair<int, int>, std::vector<double>> busy;
  std::vector<std::pair<int, int>> order;
  std::map<int, int> seen_workers;
  for (const auto& w : t.workers) {
    const std::pair<int, int> key{w.at("step").get<int>(), w.at("iteration").get<int>()};
    if (!busy.count(key)) order.push_back(key);
    busy[key].push_back(w.at("busy").get<double>());
    seen_workers[w.at("worker").get<int>()] = 1;
  }
  s.workers = static_cast<int>(seen_workers.size());
  double busy_total = 0;
  for (const auto& key : order) {
    const auto& b = busy[key];
    double sum = 0, mx = 0;
    for (double x : b) sum += x, mx = std::max(mx, x);
    busy_total += sum;
    s.imbalance.push_back(sum > 0 ? mx / (sum / b.size()) : 1.0);
  }
  if (!s.imbalance.empty()) {
    double sum = 0;
    for (double x : s.imbalance) sum += x, s.imbalance_max = std::max(s.imbalance_max, x);
    s.imbalance_mean = sum / s.imbalance.size();
    s.imbalance_last = s.imbalance.back();
    // Iterations after the first rebalance (the rebalance iteration itself pays the
    // migration and is excluded).
    const size_t from = s.first_rebalance_iteration >= 0 ? s.first_rebalance_iteration + 1 : 0;
    double after = 0;
    int n = 0;
    for (size_t i = from; i < s.imbalance.size(); ++i) after += s.imbalance[i], ++n;
    s.imbalance_after_first_rebalance = n ? after / n : s.imbalance_mean;
  }
  s.micro_efficiency = (s.workers > 0 && s.micro_lc > 0) ? busy_total / (s.workers * s.micro_lc) : 0;
  std::map<int, int> units;
  for (const auto& u : t.units) units[u.at("unit").get<int>()] = 1;
  s.units = static_cast<int>(units.size());
  s.macro_cost = macro_cost(t);
  return s;
}

nlohmann::json to_json(const MacroCost& c) {
  const auto kind = [](const MacroCost::Kind& k) {
    return nlohmann::json{{"iterations", k.count},          {"median_wall_seconds", k.wall},
                          {"median_cpu_seconds", k.cpu},    {"median_assemble_seconds", k.assemble},
                          {"median_solve_seconds", k.solve}, {"median_gmres", k.gmres}};
  };
  return {{"coordinators", c.coordinators},
          {"cpu_recorded", c.cpu_recorded},
          {"cpu_critical_seconds", c.cpu_critical},
          {"cpu_total_seconds", c.cpu_total},
          {"fluid_assembly_seconds", c.fluid_assembly},
          {"fluid_share_of_macro", c.macro_wall > 0 ? c.fluid_assembly / c.macro_wall : 0.0},
          {"factorizing", kind(c.factorizing)},
          {"kept_factor", kind(c.kept)},
          {"no_solve", kind(c.none)}};
}

nlohmann::json to_json(const TraceSummary& s) {
  return {{"iterations", s.iterations},
          {"workers", s.workers},
          {"units", s.units},
          {"entire_seconds", s.entire},
          {"micro_lc_seconds", s.micro_lc},
          {"macro_seconds", s.macro},
          {"comm1_seconds", s.comm1},
          {"comm2_seconds", s.comm2},
          {"micro_lc_over_entire", s.micro_over_entire},
          {"macro_over_entire", s.macro_over_entire},
          {"imbalance_mean", s.imbalance_mean},
          {"imbalance_max", s.imbalance_max},
          {"imbalance_after_first_rebalance", s.imbalance_after_first_rebalance},
          {"imbalance_last", s.imbalance_last},
          {"micro_phase_efficiency", s.micro_efficiency},
          {"bytes_per_unit_iteration", s.bytes_per_unit_iteration},
          {"migrations", s.migrations},
          {"first_rebalance_iteration", s.first_rebalance_iteration},
          {"macro", to_json(s.macro_cost)}};
}

}  // namespace fe2
