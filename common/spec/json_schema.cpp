#include "common/spec/json_schema.h"

#include <cmath>

namespace fe2 {

namespace {

class Emitter {
 public:
  json defs = json::object();

  json node(const SchemaNode& n, bool as_definition = false) {
    if (!n.definition.empty() && !as_definition) {
      if (!defs.contains(n.definition)) {
        defs[n.definition] = json::object();  // placeholder: a definition may recur
        defs[n.definition] = node(n, true);
      }
      return {{"$ref", "#/$defs/" + n.definition}};
    }
    json s = body(n);
    if (!n.help.empty()) s["description"] = n.help;
    if (n.def) s["default"] = *n.def;
    return s;
  }

 private:
  static void bounds(const Range& r, json& s) {
    if (std::isfinite(r.lo)) s[r.lo_open ? "exclusiveMinimum" : "minimum"] = r.lo;
    if (std::isfinite(r.hi)) s[r.hi_open ? "exclusiveMaximum" : "maximum"] = r.hi;
  }

  /// A closed object of `keys`, the discriminator (if any) fixed to `value`.
  json closed(const SchemaNode& n, const SchemaKeys* branch, const std::string& value) {
    json props = json::object(), required = json::array();
    auto add = [&](const std::string& name, const SchemaNode& k) {
      if (name == n.discriminator && branch) {
        props[name] = {{"const", value}, {"description", k.help}};
        // The default branch also matches when the discriminator is absent.
        if (!(k.def && *k.def == value)) required.push_back(name);
        return;
      }
      props[name] = node(k);
      if (k.required) required.push_back(name);
    };
    for (const auto& [name, k] : n.keys) add(name, *k);
    if (branch)
      for (const auto& [name, k] : *branch) add(name, *k);
    json s = {{"type", "object"}, {"properties", props}, {"additionalProperties", false}};
    if (!required.empty()) s["required"] = required;
    return s;
  }

  json body(const SchemaNode& n) {
    using T = SchemaNode::Type;
    json s;
    switch (n.type) {
      case T::number:
      case T::integer:
        s["type"] = n.type == T::number ? "number" : "integer";
        bounds(n.range, s);
        break;
      case T::boolean: s["type"] = "boolean"; break;
      case T::string: s["type"] = "string"; break;
      case T::choice: s = {{"type", "string"}, {"enum", n.choices}}; break;
      case T::numbers: {
        json item = {{"type", n.integer_items ? "integer" : "number"}};
        bounds(n.range, item);
        s = {{"type", "array"}, {"items", item}, {"minItems", n.size >= 0 ? n.size : 1}};
        if (n.size >= 0) s["maxItems"] = n.size;
        break;
      }
      case T::object: {
        if (n.discriminator.empty()) {
          s = closed(n, nullptr, "");
        } else {
          json branches = json::array();
          for (const auto& b : n.branches) branches.push_back(closed(n, &b.keys, b.value));
          s = {{"type", "object"}, {"oneOf", branches}};
        }
        if (!n.exactly_one_of.empty()) {
          json alternatives = json::array();
          for (const auto& k : n.exactly_one_of) alternatives.push_back({{"required", {k}}});
          if (s.contains("oneOf"))
            s = {{"type", "object"}, {"allOf", {{{"oneOf", s["oneOf"]}}, {{"oneOf", alternatives}}}}};
          else
            s["oneOf"] = alternatives;
        }
        break;
      }
      case T::map:
        s = {{"type", "object"}, {"additionalProperties", node(*n.element)}};
        if (n.min_entries > 0) s["minProperties"] = n.min_entries;
        break;
      case T::array:
        s = {{"type", "array"}, {"items", node(*n.element)}};
        if (n.min_entries > 0) s["minItems"] = n.min_entries;
        break;
      case T::custom: s = n.custom_schema; break;
    }
    return s;
  }
};

}  // namespace

json to_json_schema(const SchemaNode& root, const std::string& id, const std::string& title) {
  Emitter e;
  json body = e.node(root);
  json doc = {{"$schema", "https://json-schema.org/draft/2020-12/schema"},
              {"$id", id},
              {"title", title}};
  doc.update(body);
  if (!e.defs.empty()) doc["$defs"] = e.defs;
  return doc;
}

}  // namespace fe2
