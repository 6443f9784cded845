#pragma once
// The spec schema as data (after preCICE's XMLTag, which feeds its reader, reference and
// XSD): every key a spec may hold, with its type, default or requiredness, range and
// help; an object with a discriminator (`kind`, `cell`, `model`) has one branch of keys
// per value. The schema is the one source of truth:
//  - SpecNode reads every key by it: the reader names the key, the schema gives its
//    type, default, range, choices and help (a key the schema lacks is an internal error);
//  - `fe2heart spec-doc` prints it (spec_reference.h);
//  - `fe2heart spec-schema` emits it as JSON Schema 2020-12 (json_schema.h).
// The schemas themselves are in spec_schemas.cpp.
#include "common/spec/SpecNode.h"

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace fe2 {

struct SchemaNode;
using Schema = std::shared_ptr<const SchemaNode>;
using SchemaKeys = std::vector<std::pair<std::string, Schema>>;

/// The keys an object has when its discriminator holds `value`.
struct SchemaBranch {
  std::string value;
  SchemaKeys keys;
};

struct SchemaNode {
  enum class Type { number, integer, boolean, string, choice, numbers, object, map, array, custom };
  Type type = Type::object;
  std::string help;
  bool required = false;           ///< must be present; else optional (with `def` if it has one)
  std::optional<json> def;         ///< the value the reader uses when the key is absent
  Range range;                     ///< number, integer, and each item of `numbers`
  std::vector<std::string> choices;
  int size = -1;                   ///< numbers: the length, or -1 for any length >= 1
  bool integer_items = false;      ///< numbers: each item an integer
  SchemaKeys keys;                 ///< object: the keys of every branch
  std::string discriminator;       ///< object: the choice key (in `keys`) that picks a branch
  std::vector<SchemaBranch> branches;
  std::vector<std::string> exactly_one_of;  ///< object: exactly one of these keys is given
  Schema element;                  ///< map: each named entry; array: each item
  std::string entry_name;          ///< map: what the free names are ("name", "region")
  int min_entries = 0;             ///< map, array: at least this many entries
  std::string custom_type;         ///< custom: the type in words (the reader says the same)
  json custom_schema;              ///< custom: its JSON Schema
  std::string definition;          ///< a shared sub-schema's name ("material", "unit")

  /// The schema of `key` inside an object with this schema; `object` is the JSON
  /// object itself (its discriminator picks the branch). Null if the key is unknown.
  const SchemaNode* find(const std::string& key, const json& object) const;
  /// The keys of branch `value` (null if there is no such branch).
  const SchemaKeys* branch(const std::string& value) const;
  /// The names of the keys `object` may have (its branch's included), in schema order.
  std::vector<std::string> key_names(const json& object) const;
  /// "number > 0", "array of 3 integers in [1, 1000]", "object <material>", ...
  std::string type_text() const;
  /// "required", "optional" or "default <value>".
  std::string default_text() const;
};

/// Builders for schema tables (std::nullopt default = required).
namespace schema {
Schema number(std::optional<double> def, Range range, std::string help);
Schema integer(std::optional<int> def, Range range, std::string help);
Schema boolean(std::optional<bool> def, std::string help);
Schema string(std::optional<std::string> def, std::string help);
Schema choice(std::optional<std::string> def, std::vector<std::string> choices, std::string help);
/// Numbers, each in `items` (size -1: any length >= 1).
Schema numbers(int size, std::optional<std::vector<double>> def, std::string help,
               Range items = Range::any());
/// Numbers that must be integers in `items` (mesh divisions, components).
Schema integers(int size, std::optional<std::vector<double>> def, Range items, std::string help);
Schema object(bool required, std::string help, SchemaKeys keys);
/// An object whose `discriminator` key (a choice among `keys`) picks one of `branches`.
Schema object(bool required, std::string help, SchemaKeys keys, std::string discriminator,
              std::vector<SchemaBranch> branches);
/// An object of free names (models, probes, regions), each entry an `element`.
Schema map(bool required, std::string help, std::string entry_name, Schema element,
           int min_entries = 0);
Schema array(bool required, std::string help, Schema element, int min_items = 0);
/// A value the reader checks itself; `type` in words, `json_schema` for validators.
Schema custom(std::string type, std::string help, json json_schema);
/// A present-or-absent key without a default (e.g. one of two alternatives).
Schema optional(Schema s);
/// `s` as a key that must be present (a custom value without a default).
Schema required(Schema s);
/// `s` as a shared definition named `name` (JSON Schema $defs; its own spec-doc section).
Schema defined(std::string name, Schema s);
/// `s` with `exactly_one_of` these keys present.
Schema exactly_one_of(std::vector<std::string> keys, Schema s);
}  // namespace schema

}  // namespace fe2
