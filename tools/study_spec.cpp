#include "tools/study_spec.h"

#include <filesystem>
#include <map>
#include <regex>
#include <set>

namespace fe2 {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kKeys = {"title", "description", "base", "variants", "one_at_a_time",
                                        "reference", "quantities", "np", "mpirun"};

/// Errors of one study file, each naming the file, the key (a JSON pointer into the
/// study file), the value and what was expected.
struct StudyErrors {
  std::string file;
  [[noreturn]] void bad(const std::string& key, const json& value, const std::string& expected) const {
    throw InputError(fmt::format("study file '{}': {}: got {}, expected {}", file, key,
                                 value.dump(), expected));
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("study file '{}': {}: {}", file, key, what));
  }
  void only_keys(const json& j, const std::string& where, const std::vector<std::string>& keys) const {
    for (const auto& [k, v] : j.items())
      if (std::find(keys.begin(), keys.end(), k) == keys.end()) {
        const std::string near = closest_match(k, keys);
        fail(where.empty() ? "/" : where,
             fmt::format("unknown key '{}'{}; expected one of {}", k,
                         near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                         fmt::join(keys, ", ")));
      }
  }
};

/// "/" inside a key is "~1" in a pointer (RFC 6901).
std::string escape_token(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return out;
}

const char* type_word(const json& v) {
  if (v.is_number()) return "a number";
  if (v.is_boolean()) return "true or false";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  if (v.is_object()) return "an object";
  return "null";
}

/// A value as a folder-name fragment: 8, 1e-06, adaptive, 4x2x2.
std::string value_word(const json& v) {
  std::string w;
  if (v.is_string()) w = v.get<std::string>();
  else if (v.is_array()) {
    for (const auto& x : v) {
      if (!w.empty()) w += 'x';
      w += value_word(x);
    }
  } else w = v.dump();
  for (char& c : w)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '+' && c != '_') c = '_';
  return w;
}

/// Applies {"/pointer": value} to `spec`: the pointer's parent must be an object or
/// array of the base spec, and a value replacing one must have its JSON type.
void apply_set(json& spec, const json& base, const json& set, const std::string& where,
               const StudyErrors& err) {
  if (!set.is_object())
    err.bad(where, set, "an object {\"/json/pointer\": value, ...} (RFC 6901 pointers into the base spec)");
  for (const auto& [key, value] : set.items()) {
    const std::string at = where + "/" + escape_token(key);
    json::json_pointer p;
    try {
      p = json::json_pointer(key);
    } catch (const json::exception& e) {
      err.fail(at, fmt::format("'{}' is not a JSON pointer ({}); expected e.g. \"/time/steps\"", key, e.what()));
    }
    if (p.empty())
      err.fail(at, "the empty pointer would replace the whole base spec; expected a key such as \"/time/steps\"");
    const json::json_pointer parent = p.parent_pointer();
    if (!base.contains(parent) || !(base.at(parent).is_object() || base.at(parent).is_array()))
      err.fail(at, fmt::format("'{}' is not in the base spec: it has no object '{}'; expected a pointer "
                               "to a key of the base spec (or a new key of one of its objects)",
                               key, parent.to_string()));
    if (base.at(parent).is_array() && !base.contains(p))
      err.fail(at, fmt::format("'{}' is not in the base spec: '{}' has {} entries; expected an index below that",
                               key, parent.to_string(), base.at(parent).size()));
    if (base.contains(p)) {
      const json& old = base.at(p);
      const bool same = (old.is_number() && value.is_number()) || old.type() == value.type() || old.is_null();
      if (!same)
        err.bad(at, value, fmt::format("{} like the base spec's {} = {}", type_word(old), key, old.dump()));
    }
    spec[p] = value;
  }
}

/// File paths of a spec ("file", "mesh_file" anywhere) made absolute against the base
/// spec's folder, so a variant's spec works from DIR/variants/<name>/.
void absolute_paths(json& j, const fs::path& dir) {
  if (j.is_array())
    for (json& x : j) absolute_paths(x, dir);
  if (!j.is_object()) return;
  for (auto& [k, v] : j.items()) {
    if ((k == "file" || k == "mesh_file") && v.is_string()) {
      const fs::path p = v.get<std::string>();
      if (p.is_relative()) v = fs::weakly_canonical(dir / p).string();
    } else {
      absolute_paths(v, dir);
    }
  }
}

void read_reference(const json& r, const fs::path& dir, const std::set<std::string>& names,
                    const StudyErrors& err, StudySpec& s) {
  if (r.is_string() && r == "finest") {
    s.reference = StudySpec::Reference::finest;
  } else if (r.is_string()) {
    if (!names.count(r.get<std::string>()))
      err.bad("/reference", r, fmt::format("\"finest\", {{\"run\": DIR}} or a variant name: {}", fmt::join(names, ", ")));
    s.reference = StudySpec::Reference::variant;
    s.reference_variant = r;
  } else if (r.is_object() && r.size() == 1 && r.contains("run") && r["run"].is_string()) {
    s.reference = StudySpec::Reference::run;
    s.reference_run = (dir / r["run"].get<std::string>()).lexically_normal().string();
    if (!fs::is_regular_file(fs::path(s.reference_run) / "summary.json"))
      err.bad("/reference/run", r["run"],
              fmt::format("the folder of an earlier run, holding summary.json ('{}/summary.json' does not exist)",
                          s.reference_run));
  } else {
    err.bad("/reference", r, "\"finest\", a variant name, or {\"run\": \"DIR of an earlier run\"}");
  }
}

void read_quantities(const json& j, const StudyErrors& err, StudySpec& s) {
  const auto& known = study_quantity_names();
  if (!j.contains("quantities")) {
    // What the base scene has: probes, cavities, circulation pressures.
    if (s.base_spec.contains("probes")) s.quantities.push_back("displacement");
    if (s.base_spec.contains("cavities")) s.quantities.push_back("cavity_volumes");
    if (s.base_spec.contains("circulation")) s.quantities.push_back("cavity_pressures");
    if (s.quantities.empty())
      err.fail("/quantities", "missing, and the base spec has no probes or cavities to compare; expected "
                              "e.g. [\"displacement\"] with probes in the base spec");
    return;
  }
  const json& q = j["quantities"];
  if (!q.is_array() || q.empty())
    err.bad("/quantities", q, "a non-empty array of quantity names or summary.json pointers");
  for (size_t i = 0; i < q.size(); ++i) {
    const std::string where = fmt::format("/quantities/{}", i);
    if (!q[i].is_string()) err.bad(where, q[i], "a string");
    const std::string name = q[i];
    if (name.rfind('/', 0) == 0) {
      try {
        (void)json::json_pointer(name);
      } catch (const json::exception& e) {
        err.fail(where, fmt::format("'{}' is not a JSON pointer ({})", name, e.what()));
      }
    } else if (std::find(known.begin(), known.end(), name) == known.end()) {
      const std::string near = closest_match(name, known);
      err.bad(where, q[i],
              fmt::format("one of {}{}, or a JSON pointer into summary.json such as \"/circulation/cavities/lv/EF\"",
                          fmt::join(known, ", "), near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
    }
    s.quantities.push_back(name);
  }
}

}  // namespace

const std::vector<std::string>& study_quantity_names() {
  static const std::vector<std::string> names = {"displacement", "probes", "cavity_volumes",
                                                 "cavity_pressures", "load_pressures"};
  return names;
}

bool is_study_spec(const json& j) {
  return j.is_object() && j.contains("base") && (j.contains("variants") || j.contains("one_at_a_time"));
}

StudySpec read_study_spec(const std::string& file) {
  StudySpec s;
  s.file = file;
  const StudyErrors err{file};
  const json j = read_json_file(file);
  if (!j.is_object()) err.bad("/", j, "an object with \"base\" and \"variants\"");
  err.only_keys(j, "", kKeys);
  const fs::path dir = fs::path(file).parent_path();
  if (j.contains("title")) {
    if (!j["title"].is_string()) err.bad("/title", j["title"], "a string");
    s.title = j["title"];
  }

  if (!j.contains("base"))
    err.fail("/base", "missing; expected the path of the base run spec (relative to the study file)");
  if (!j["base"].is_string()) err.bad("/base", j["base"], "a string: the path of the base run spec");
  s.base = (dir / j["base"].get<std::string>()).lexically_normal().string();
  try {
    s.base_spec = read_json_file(s.base);
  } catch (const InputError& e) {
    err.fail("/base", fmt::format("cannot read the base spec: {}", e.what()));
  }
  if (!s.base_spec.is_object()) err.fail("/base", fmt::format("the base spec '{}' is not a JSON object", s.base));
  const fs::path base_dir = fs::path(s.base).parent_path();

  static const std::regex name_ok("[A-Za-z0-9_.+=-]{1,80}");
  std::set<std::string> names;
  auto add = [&](const std::string& name, const json& set, const std::string& where, const std::string& set_where) {
    if (!std::regex_match(name, name_ok))
      err.bad(where + "/name", name, "1 to 80 letters, digits or _.+=- (it names the variant's folder)");
    if (!names.insert(name).second) err.bad(where + "/name", name, "a name no other variant has");
    StudyVariant v{name, set, s.base_spec};
    apply_set(v.spec, s.base_spec, set, set_where, err);
    absolute_paths(v.spec, base_dir);
    s.variants.push_back(std::move(v));
  };

  if (j.contains("variants")) {
    const json& vs = j["variants"];
    if (!vs.is_array()) err.bad("/variants", vs, "an array of {\"name\": ..., \"set\": {\"/pointer\": value}}");
    for (size_t i = 0; i < vs.size(); ++i) {
      const std::string where = fmt::format("/variants/{}", i);
      if (!vs[i].is_object()) err.bad(where, vs[i], "an object {\"name\": ..., \"set\": {...}}");
      err.only_keys(vs[i], where, {"name", "set"});
      if (!vs[i].contains("name") || !vs[i]["name"].is_string())
        err.bad(where + "/name", vs[i].value("name", json()), "a string naming the variant");
      if (!vs[i].contains("set"))
        err.fail(where + "/set", "missing; expected {\"/pointer\": value, ...} ({} for the base unchanged)");
      add(vs[i]["name"], vs[i]["set"], where, where + "/set");
    }
  }
  if (j.contains("one_at_a_time")) {
    const json& oat = j["one_at_a_time"];
    if (!oat.is_object()) err.bad("/one_at_a_time", oat, "an object {\"/pointer\": [value, ...]}");
    // Names from the pointer's last key ("steps=4"), or its whole path if two pointers share it.
    std::map<std::string, int> last_count;
    for (const auto& [key, values] : oat.items()) ++last_count[key.substr(key.find_last_of('/') + 1)];
    for (const auto& [key, values] : oat.items()) {
      const std::string where = "/one_at_a_time/" + escape_token(key);
      if (!values.is_array() || values.empty())
        err.bad(where, values, "a non-empty array of values, one variant each");
      std::string stem = key.substr(key.find_last_of('/') + 1);
      if (last_count[stem] > 1) stem = value_word(key.substr(1));
      for (const json& value : values)
        add(stem + "=" + value_word(value), json{{key, value}}, where, "/one_at_a_time");
    }
  }
  if (s.variants.empty())
    err.fail("/variants", "no variants; expected \"variants\" or \"one_at_a_time\" with at least one");

  if (j.contains("reference")) read_reference(j["reference"], dir, names, err, s);
  read_quantities(j, err, s);

  if (j.contains("np")) {
    const json& np = j["np"];
    if (!np.is_number_integer() || np.get<long long>() < 1 || np.get<long long>() > 100000)
      err.bad("/np", np, "an integer from 1 to 100000 (ranks per variant)");
    s.np = np.get<int>();
  }
  if (j.contains("mpirun")) {
    const json& m = j["mpirun"];
    if (!m.is_array() || m.empty())
      err.bad("/mpirun", m, "a non-empty array of strings, e.g. [\"mpirun\", \"-n\", \"{np}\"]");
    for (const json& x : m) {
      if (!x.is_string()) err.bad("/mpirun", m, "an array of strings, e.g. [\"mpirun\", \"-n\", \"{np}\"]");
      s.mpirun.push_back(x);
    }
  }
  return s;
}

}  // namespace fe2
