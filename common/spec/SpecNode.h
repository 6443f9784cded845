#pragma once
// Reading a JSON run spec with every key declared once: name, default, allowed
// range and help (after deal.II step-44's Parameters and preCICE's XMLTag).
//
// A SpecNode is a view on one JSON object at a JSON-pointer path ("/macro/mesh").
// Each accessor declares a key and reads it; finish() then rejects any key that was
// not declared ("unknown key 'tol_newton' in /solver; did you mean 'newton_tol'?").
// Every error is an fe2::InputError naming the path, the value and what is expected.
// A node may carry its part of the spec schema (SchemaNode.h, the one declaration of
// every key, which `fe2heart spec-doc` and `spec-schema` print): each accessor then
// checks that the key it reads is in the schema with the same type, default and range,
// and a disagreement is an internal error (fe2::Error, exit 1), never the user's.
#include "common/error.h"

#include <nlohmann/json.hpp>

#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace fe2 {

using json = nlohmann::json;

struct SchemaNode;

/// What a read visited: the schema node of every key read (for the test that every
/// key of the schema is read by some spec).
struct SpecDoc {
  std::set<const SchemaNode*> visited;
};

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;  ///< true: value must be > lo (else >= lo)
  bool hi_open = false;
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range any() { return {}; }
  bool contains(double v) const;
  std::string describe() const;
};

class SpecNode {
 public:
  /// `doc` and `schema` (this object's schema) are lent, may be null; they must outlive
  /// this node and its children.
  SpecNode(const json& j, std::string path, SpecDoc* doc = nullptr,
           const SchemaNode* schema = nullptr);

  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const;
  bool has(const std::string& key) const;
  const json& raw() const { return *j_; }

  double number(const std::string& key, std::optional<double> def, Range range,
                const std::string& help);
  int integer(const std::string& key, std::optional<int> def, Range range,
              const std::string& help);
  bool boolean(const std::string& key, std::optional<bool> def, const std::string& help);
  std::string string(const std::string& key, std::optional<std::string> def,
                     const std::string& help);
  /// A string from a fixed set of choices.
  std::string choice(const std::string& key, std::optional<std::string> def,
                     const std::vector<std::string>& choices, const std::string& help);
  /// A fixed-length array of numbers (size < 0: any length >= 1).
  std::vector<double> numbers(const std::string& key, int size,
                              std::optional<std::vector<double>> def,
                              const std::string& help);
  /// A nested object; if absent and not required, an empty object.
  SpecNode child(const std::string& key, bool required, const std::string& help);
  /// An object whose keys are free names (e.g. probes, models): declares the key,
  /// returns the names in order.
  std::vector<std::string> names(const std::string& key, const std::string& help) const;
  /// An array of objects.
  std::vector<SpecNode> children(const std::string& key, bool required,
                                 const std::string& help);

  /// Declares a key whose value the caller checks itself; null if absent.
  const json* declared_value(const std::string& key, const std::string& type,
                             const std::string& help);

  /// Rejects undeclared keys. Call after all keys of this object are read.
  void finish() const;

  /// Throws InputError "<path>/<key>: got <value>, expected <what>".
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;

 private:
  const json* lookup(const std::string& key) const;
  /// Declares `key` as the reader sees it; returns its schema (null without a schema).
  const SchemaNode* declare(const std::string& key, const std::shared_ptr<const SchemaNode>& reader);

  const json* j_;
  std::string path_;
  SpecDoc* doc_;
  const SchemaNode* schema_;
  mutable std::vector<std::string> declared_;
  static const json& empty_object();
};

/// Reads a JSON file; a missing or malformed file is an InputError naming it.
json read_json_file(const std::string& file);
/// Parses spec text as read_json_file does (duplicate keys, depth, overflow are
/// InputErrors naming `file`).
json parse_json_text(std::string_view text, const std::string& file);

/// Closest candidate by edit distance, or "" when nothing is close.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);

}  // namespace fe2
