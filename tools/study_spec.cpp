#include "tools/study_spec.h"

#include "common/spec/SchemaNode.h"

#include <filesystem>
#include <map>
#include <regex>
#include <set>

namespace fe2 {

namespace fs = std::filesystem;

namespace {

/// Errors of the values a study's custom keys hold, each naming the key (a JSON pointer
/// into the study file), the value and what was expected; read_study_spec adds the file.
struct StudyErrors {
  [[noreturn]] void bad(const std::string& key, const json& value, const std::string& expected) const {
    throw InputError(fmt::format("{}: got {}, expected {}", key, value.dump(), expected));
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("{}: {}", key, what));
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

void read_reference(SpecNode& root, const fs::path& dir, const std::set<std::string>& names,
                    const StudyErrors& err, StudySpec& s) {
  const json* ref = root.declared_value("reference");
  if (!ref) return;  // the finest variant
  const json& r = *ref;
  const std::vector<std::string> known(names.begin(), names.end());
  if (r.is_string() && r == "finest") {
    s.reference = StudySpec::Reference::finest;
  } else if (r.is_string()) {
    if (!names.count(r.get<std::string>()))
      err.bad("/reference", r,
              known_names("\"finest\", {\"run\": DIR} or a variant name", r.get<std::string>(), known));
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
    err.bad("/reference", r, root.expected("reference"));
  }
}

void read_quantities(SpecNode& root, const StudyErrors& err, StudySpec& s) {
  const auto& known = study_quantity_names();
  const json* given = root.declared_value("quantities");
  if (!given) {
    // What the base scene has: probes, cavities, circulation pressures.
    if (s.base_spec.contains("probes")) s.quantities.push_back("displacement");
    if (s.base_spec.contains("cavities")) s.quantities.push_back("cavity_volumes");
    if (s.base_spec.contains("circulation")) s.quantities.push_back("cavity_pressures");
    if (s.quantities.empty())
      err.fail("/quantities", "missing, and the base spec has no probes or cavities to compare; expected "
                              "e.g. [\"displacement\"] with probes in the base spec");
    return;
  }
  const json& q = *given;
  if (!q.is_array() || q.empty()) err.bad("/quantities", q, root.expected("quantities"));
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
      err.bad(where, q[i],
              known_names("a quantity name", name, known) +
                  ", or a JSON pointer into summary.json such as \"/circulation/cavities/lv/EF\"");
    }
    s.quantities.push_back(name);
  }
}

const char* const kNameHelp = "1 to 80 letters, digits or _.+=- (it names the variant's folder)";

Schema make_study_spec_schema() {
  using namespace schema;
  using std::nullopt;
  const json strings = {{"type", "array"}, {"minItems", 1}, {"items", {{"type", "string"}}}};
  json quantity = {{"anyOf", {{{"enum", study_quantity_names()}}, {{"type", "string"}, {"pattern", "^/"}}}}};
  return object(
      true, "a study file (fe2heart study): variants of a base run spec compared with a reference",
      {{"title", string("", "one line saying what the study compares")},
       {"description", string("", "what the study shows and how to run it")},
       {"base", string(nullopt, "path of the base run spec (relative to the study file)")},
       {"variants",
        array(false, "variants of the base, each a name and the edits that make it",
              object(true, "a variant",
                     {{"name", string(nullopt, kNameHelp)},
                      {"set", required(custom("object {\"/pointer\": value}",
                                              "what differs from the base: RFC 6901 pointers into the "
                                              "base spec with their values ({} for the base unchanged)",
                                              {{"type", "object"}}))}}))},
       {"one_at_a_time",
        custom("object {\"/pointer\": [value, ...]}",
               "one variant per value of each pointer, named after the pointer's last key "
               "(\"steps=4\"); with \"variants\", or instead of it",
               {{"type", "object"}, {"additionalProperties", {{"type", "array"}, {"minItems", 1}}}})},
       {"reference",
        custom("\"finest\", a variant name or {\"run\": DIR}",
               "what every variant is compared with: the finest variant (default), a named variant, "
               "or the folder of an earlier run",
               {{"anyOf",
                 {{{"type", "string"}},
                  {{"type", "object"},
                   {"properties", {{"run", {{"type", "string"}}}}},
                   {"required", {"run"}},
                   {"additionalProperties", false}}}}})},
       {"quantities",
        custom("array of quantity names or summary.json pointers",
               fmt::format("what is compared: {}, or JSON pointers into summary.json such as "
                           "\"/circulation/cavities/lv/EF\"; default: what the base has (probes, "
                           "cavities, circulation)",
                           fmt::join(study_quantity_names(), ", ")),
               {{"type", "array"}, {"minItems", 1}, {"items", quantity}})},
       {"np", integer(1, Range::closed(1, 100000), "ranks per variant (or --np)")},
       {"mpirun", custom("array of strings",
                         "the launcher of each variant, \"{np}\" standing for its ranks; default: "
                         "mpirun -n NP for NP > 1, the binary alone for NP = 1",
                         strings)}});
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

const SchemaNode& study_spec_schema() {
  static const Schema s = make_study_spec_schema();
  return *s;
}

namespace {

StudySpec read_study(const std::string& file, SpecDoc* doc) {
  StudySpec s;
  s.file = file;
  const StudyErrors err;
  const json j = read_json_file(file);
  if (!j.is_object()) err.bad("/", j, "an object with \"base\" and \"variants\"");
  SpecNode root(j, "", study_spec_schema(), doc);
  const fs::path dir = fs::path(file).parent_path();
  s.title = root.string("title");
  root.string("description");

  s.base = (dir / root.string("base")).lexically_normal().string();
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
    if (!std::regex_match(name, name_ok)) err.bad(where + "/name", name, kNameHelp);
    if (!names.insert(name).second) err.bad(where + "/name", name, "a name no other variant has");
    StudyVariant v{name, set, s.base_spec};
    apply_set(v.spec, s.base_spec, set, set_where, err);
    absolute_paths(v.spec, base_dir);
    s.variants.push_back(std::move(v));
  };

  for (SpecNode& v : root.children("variants")) {
    const std::string name = v.string("name");
    const json* set = v.declared_value("set");  // required: never null
    v.finish();
    add(name, *set, v.path(), v.key_path("set"));
  }
  if (const json* oat = root.declared_value("one_at_a_time")) {
    if (!oat->is_object()) err.bad("/one_at_a_time", *oat, root.expected("one_at_a_time"));
    // Names from the pointer's last key ("steps=4"), or its whole path if two pointers share it.
    std::map<std::string, int> last_count;
    for (const auto& [key, values] : oat->items()) ++last_count[key.substr(key.find_last_of('/') + 1)];
    for (const auto& [key, values] : oat->items()) {
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

  read_reference(root, dir, names, err, s);
  read_quantities(root, err, s);
  s.np = root.integer("np");
  if (const json* m = root.declared_value("mpirun")) {
    if (!m->is_array() || m->empty()) err.bad("/mpirun", *m, root.expected("mpirun") + ", e.g. [\"mpirun\", \"-n\", \"{np}\"]");
    for (const json& x : *m) {
      if (!x.is_string()) err.bad("/mpirun", *m, root.expected("mpirun") + ", e.g. [\"mpirun\", \"-n\", \"{np}\"]");
      s.mpirun.push_back(x);
    }
  }
  root.finish();
  return s;
}

}  // namespace

StudySpec read_study_spec(const std::string& file, SpecDoc* doc) {
  try {
    return read_study(file, doc);
  } catch (const InputError& e) {
    throw InputError(fmt::format("study file '{}': {}", file, e.what()));
  }
}

}  // namespace fe2
