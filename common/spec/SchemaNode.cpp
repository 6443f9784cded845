#include "common/spec/SchemaNode.h"

#include "common/error.h"

#include <cmath>

namespace fe2 {

namespace {

const SchemaNode* find_in(const SchemaKeys& keys, const std::string& key) {
  for (const auto& [name, node] : keys)
    if (name == key) return node.get();
  return nullptr;
}

std::string quoted_list(const std::vector<std::string>& v) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? ", \"" : "\"") + v[i] + "\"";
  return out;
}

/// A value as a user writes it: 1 and 5000000000 rather than 1.0 and 5000000000.0.
std::string show(const json& v) {
  if (v.is_number_float()) return fmt::format("{}", v.get<double>());
  if (v.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + show(v[i]);
    return out + "]";
  }
  return v.dump();
}

std::shared_ptr<SchemaNode> make(SchemaNode::Type type, std::string help) {
  auto n = std::make_shared<SchemaNode>();
  n->type = type;
  n->help = std::move(help);
  return n;
}

template <class T>
void set_default(SchemaNode& n, const std::optional<T>& def) {
  n.required = !def.has_value();
  if (def) n.def = json(*def);
}

}  // namespace

const SchemaKeys* SchemaNode::branch(const std::string& value) const {
  for (const auto& b : branches)
    if (b.value == value) return &b.keys;
  return nullptr;
}

namespace {

/// The branch `object` selects by its discriminator (or the discriminator's default).
const SchemaKeys* branch_of(const SchemaNode& n, const json& object) {
  if (n.discriminator.empty()) return nullptr;
  std::string value;
  auto it = object.find(n.discriminator);
  if (it != object.end() && it->is_string()) value = it->get<std::string>();
  else if (const SchemaNode* d = find_in(n.keys, n.discriminator); d && d->def) value = d->def->get<std::string>();
  return n.branch(value);
}

}  // namespace

const SchemaNode* SchemaNode::find(const std::string& key, const json& object) const {
  if (type == Type::map) return element.get();
  if (type != Type::object) return nullptr;
  if (const SchemaNode* n = find_in(keys, key)) return n;
  const SchemaKeys* b = branch_of(*this, object);
  return b ? find_in(*b, key) : nullptr;
}

std::vector<std::string> SchemaNode::key_names(const json& object) const {
  std::vector<std::string> out;
  if (type != Type::object) return out;
  for (const auto& [name, _] : keys) out.push_back(name);
  if (const SchemaKeys* b = branch_of(*this, object))
    for (const auto& [name, _] : *b) out.push_back(name);
  return out;
}

std::string SchemaNode::type_text() const {
  switch (type) {
    case Type::number: return "number " + range.describe();
    case Type::integer: return "integer " + range.describe();
    case Type::boolean: return "boolean";
    case Type::string: return "string";
    case Type::choice: return "one of " + quoted_list(choices);
    case Type::numbers: {
      const bool bounded = std::isfinite(range.lo) || std::isfinite(range.hi);
      // fmt, not operator+: GCC 12 -O3 reports a false -Wrestrict in the concatenation.
      const std::string what = bounded ? fmt::format("{} {}", integer_items ? "integers" : "numbers", range.describe())
                                       : std::string(integer_items ? "integers" : "numbers");
      return size >= 0 ? fmt::format("array of {} {}", size, what) : "non-empty array of " + what;
    }
    case Type::object: return definition.empty() ? "object" : "object <" + definition + ">";
    case Type::map:
      return fmt::format("object {{<{}>: {}}}", entry_name, element->type_text());
    case Type::array: return "array of " + element->type_text();
    case Type::custom: return custom_type;
  }
  return "?";
}

std::string SchemaNode::default_text() const {
  if (required) return "required";
  if (def) return "default " + show(*def);
  return "optional";
}

namespace schema {

Schema number(std::optional<double> def, Range range, std::string help) {
  auto n = make(SchemaNode::Type::number, std::move(help));
  set_default(*n, def);
  n->range = range;
  return n;
}

Schema integer(std::optional<int> def, Range range, std::string help) {
  auto n = make(SchemaNode::Type::integer, std::move(help));
  set_default(*n, def);
  n->range = range;
  return n;
}

Schema boolean(std::optional<bool> def, std::string help) {
  auto n = make(SchemaNode::Type::boolean, std::move(help));
  set_default(*n, def);
  return n;
}

Schema string(std::optional<std::string> def, std::string help) {
  auto n = make(SchemaNode::Type::string, std::move(help));
  set_default(*n, def);
  return n;
}

Schema choice(std::optional<std::string> def, std::vector<std::string> choices, std::string help) {
  auto n = make(SchemaNode::Type::choice, std::move(help));
  set_default(*n, def);
  n->choices = std::move(choices);
  return n;
}

Schema numbers(int size, std::optional<std::vector<double>> def, std::string help,
               Range items) {
  auto n = make(SchemaNode::Type::numbers, std::move(help));
  set_default(*n, def);
  n->size = size;
  n->range = items;
  return n;
}

Schema integers(int size, std::optional<std::vector<double>> def, Range items, std::string help) {
  auto n = std::const_pointer_cast<SchemaNode>(numbers(size, std::move(def), std::move(help), items));
  n->integer_items = true;
  if (n->def)  // shown and emitted as integers; equal to the reader's doubles
    for (auto& x : *n->def) x = static_cast<long long>(x.get<double>());
  return n;
}

Schema object(bool required, std::string help, SchemaKeys keys) {
  auto n = make(SchemaNode::Type::object, std::move(help));
  n->required = required;
  n->keys = std::move(keys);
  return n;
}

Schema object(bool required, std::string help, SchemaKeys keys, std::string discriminator,
              std::vector<SchemaBranch> branches) {
  auto n = std::const_pointer_cast<SchemaNode>(object(required, std::move(help), std::move(keys)));
  const SchemaNode* d = find_in(n->keys, discriminator);
  FE2_CHECK(d && d->type == SchemaNode::Type::choice, "discriminator '{}' must be a choice key",
            discriminator);
  std::vector<std::string> values;
  for (const auto& b : branches) values.push_back(b.value);
  FE2_CHECK(values == d->choices, "branches of '{}' must be its choices, in order", discriminator);
  n->discriminator = std::move(discriminator);
  n->branches = std::move(branches);
  return n;
}

Schema map(bool required, std::string help, std::string entry_name, Schema element,
           int min_entries) {
  auto n = make(SchemaNode::Type::map, std::move(help));
  n->required = required;
  n->entry_name = std::move(entry_name);
  n->element = std::move(element);
  n->min_entries = min_entries;
  return n;
}

Schema array(bool required, std::string help, Schema element, int min_items) {
  auto n = make(SchemaNode::Type::array, std::move(help));
  n->required = required;
  n->element = std::move(element);
  n->min_entries = min_items;
  return n;
}

Schema custom(std::string type, std::string help, json json_schema) {
  auto n = make(SchemaNode::Type::custom, std::move(help));
  n->custom_type = std::move(type);
  n->custom_schema = std::move(json_schema);
  return n;
}

Schema optional(Schema s) {
  auto n = std::make_shared<SchemaNode>(*s);
  n->required = false;
  n->def.reset();
  return n;
}

Schema required(Schema s) {
  auto n = std::make_shared<SchemaNode>(*s);
  n->required = true;
  n->def.reset();
  return n;
}

Schema defined(std::string name, Schema s) {
  auto n = std::make_shared<SchemaNode>(*s);
  n->definition = std::move(name);
  return n;
}

Schema exactly_one_of(std::vector<std::string> keys, Schema s) {
  auto n = std::make_shared<SchemaNode>(*s);
  n->exactly_one_of = std::move(keys);
  return n;
}

}  // namespace schema

}  // namespace fe2
