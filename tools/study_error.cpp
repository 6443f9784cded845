#include "tools/study_error.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fe2 {

namespace {

/// Every number in `j` (a number, or arrays/objects of them, in key order).
void flatten(const json& j, std::vector<double>& out, bool& ok) {
  if (j.is_number()) out.push_back(j.get<double>());
  else if (j.is_array() || j.is_object())
    for (const auto& x : j) flatten(x, out, ok);
  else ok = false;
}

}  // namespace

QuantitySeries read_quantity(const std::string& dir, const std::string& q) {
  const std::string file = (std::filesystem::path(dir) / "summary.json").string();
  const json s = read_json_file(file);
  QuantitySeries out;
  if (q.rfind('/', 0) == 0) {
    const json::json_pointer p(q);
    if (!s.contains(p))
      throw InputError(fmt::format("{}: no '{}' (quantity '{}'); expected a key of summary.json", file, q, q));
    bool ok = true;
    out.value.emplace_back();
    flatten(s.at(p), out.value.back(), ok);
    if (!ok || out.value.back().empty())
      throw InputError(fmt::format("{}: '{}' is {}, expected a number or numbers", file, q, s.at(p).dump()));
    return out;
  }
  json probes_X;  // reference positions of the probes, for "displacement"
  if (q == "displacement") {
    const json spec = read_json_file((std::filesystem::path(dir) / "spec.json").string());
    probes_X = spec.value("probes", json::object());
  }
  for (const json& h : s.value("history", json::array())) {
    std::vector<double> v;
    if (q == "displacement" || q == "probes") {
      if (!h.contains("probes")) continue;
      for (const auto& [name, x] : h["probes"].items())
        for (int k = 0; k < 3; ++k)
          v.push_back(x[k].get<double>() - (q == "displacement" ? probes_X.at(name)[k].get<double>() : 0.0));
    } else if (q == "cavity_volumes") {
      if (!h.contains("cavity_volumes")) continue;
      for (const auto& [name, V] : h["cavity_volumes"].items()) v.push_back(V.get<double>());
    } else if (q == "cavity_pressures") {
      if (!h.contains("circulation")) continue;
      for (const auto& [name, c] : h["circulation"].items()) v.push_back(c.at("pressure").get<double>());
    } else if (q == "load_pressures") {
      if (!h.contains("load_pressures")) continue;
      for (const auto& p : h["load_pressures"]) v.push_back(p.get<double>());
    } else {
      throw InputError(fmt::format("unknown study quantity '{}'", q));
    }
    out.time.push_back(h.at("time").get<double>());
    out.value.push_back(std::move(v));
  }
  if (out.time.empty())
    throw InputError(fmt::format("{}: no step has '{}' (no probes, cavities or circulation in the run?)", file, q));
  return out;
}

QuantityError compare_quantity(const QuantitySeries& run, const QuantitySeries& ref) {
  QuantityError e;
  double diff = 0, scale = 0;
  auto add = [&](const std::vector<double>& a, const std::vector<double>& b) {
    for (size_t i = 0; i < a.size(); ++i) {
      diff = std::max(diff, std::abs(a[i] - b[i]));
      scale = std::max(scale, std::abs(b[i]));
    }
    ++e.times;
  };
  const size_t width = ref.value.empty() ? 0 : ref.value.front().size();
  for (const auto& v : run.value)
    if (v.size() != width) {
      e.note = fmt::format("{} entries against the reference's {} (different probes or cavities?)", v.size(), width);
      return e;
    }
  if (run.time.empty() != ref.time.empty()) {
    e.note = "one run has the quantity per step, the other once";
    return e;
  }
  if (run.time.empty()) {
    add(run.value.front(), ref.value.front());
  } else {
    const double t0 = ref.time.front(), t1 = ref.time.back();
    const double eps = 1e-9 * std::max({std::abs(t0), std::abs(t1), 1e-300});
    for (size_t k = 0; k < run.time.size(); ++k) {
      const double t = run.time[k];
      if (t < t0 - eps || t > t1 + eps) continue;
      // The reference segment [t_i, t_{i+1}] holding t; exact at its ends.
      size_t i = std::upper_bound(ref.time.begin(), ref.time.end(), t + eps) - ref.time.begin();
      i = i == 0 ? 0 : i - 1;
      std::vector<double> r = ref.value[i];
      if (i + 1 < ref.time.size() && std::abs(t - ref.time[i]) > eps) {
        const double w = (t - ref.time[i]) / (ref.time[i + 1] - ref.time[i]);
        for (size_t c = 0; c < r.size(); ++c) r[c] = (1 - w) * ref.value[i][c] + w * ref.value[i + 1][c];
      }
      add(run.value[k], r);
    }
  }
  if (e.times == 0) {
    e.note = "no step time within the reference's";
    return e;
  }
  if (scale > 0) {
    e.error = diff / scale;
  } else {
    e.error = diff;
    e.note = "absolute (reference 0)";
  }
  return e;
}

}  // namespace fe2
