#pragma once
// Reading a JSON spec whose every key is declared once, in the spec schema (SchemaNode.h:
// name, type, default, range and help; after preCICE's XMLTag, which feeds its reader).
//
// A SpecNode is a view on one JSON object at a JSON-pointer path ("/macro/mesh") with
// that object's schema. Each accessor names a key only: the default, range and help
// come from the schema, so a reader cannot state its own (nor drift from what
// `fe2heart spec-doc` and `spec-schema` print). finish() then rejects any key that was
// not read ("unknown key 'tol_newton' in /solver; did you mean 'newton_tol'?").
// Every error is an fe2::InputError naming the path, the value and what is expected in
// the schema's words; a read of a key the schema lacks is an internal error (fe2::Error,
// exit 1), never the user's.
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
  /// `schema` is this object's schema; `doc` and `schema` are lent (doc may be null)
  /// and must outlive this node and its children.
  SpecNode(const json& j, std::string path, const SchemaNode& schema, SpecDoc* doc = nullptr);

  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const;
  bool has(const std::string& key) const;
  const json& raw() const { return *j_; }

  // Each accessor reads `key` as its schema node declares it: type, default (absent:
  // the default, or an InputError if the schema has none), range, choices, length and
  // help (the wording of every error). A key the schema lacks here, or declares with
  // another type, is an internal error (fe2::Error).
  double number(const std::string& key);
  int integer(const std::string& key);
  bool boolean(const std::string& key);
  std::string string(const std::string& key);
  /// A string from the schema's choices.
  std::string choice(const std::string& key);
  /// An array of numbers (the schema's length, range, and integers if it says so).
  std::vector<double> numbers(const std::string& key);
  /// A nested object (or an entry of a map of free names); if absent and not
  /// required, an empty object.
  SpecNode child(const std::string& key);
  /// An array of objects.
  std::vector<SpecNode> children(const std::string& key);
  /// A key whose value the caller checks itself (a custom type); null if absent.
  const json* declared_value(const std::string& key);

  /// "a number > 0 (end time)": what the schema expects of `key`, for the caller's own
  /// checks of a value the schema cannot express.
  std::string expected(const std::string& key) const;

  /// Rejects undeclared keys. Call after all keys of this object are read.
  void finish() const;

  /// Throws InputError "<path>/<key>: got <value>, expected <what>".
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;

 private:
  const json* lookup(const std::string& key) const;
  /// The schema node of `key`, which must have the type the accessor `reader` reads
  /// (else an internal error); records the key as declared.
  const SchemaNode& declare(const std::string& key, const char* reader);
  const SchemaNode& schema_of(const std::string& key, const char* reader) const;

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

// Every error that refuses a name (a key, node set, face, region, model, cavity,
// choice, quantity...) says it through these, so each suggests the nearest the same way.
/// "; did you mean \"top\"?" for the candidate nearest `name`, or "" when none is close.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known,
                         char quote = '"');
/// `what` with the known names and the nearest: "a node set of the mesh (top, bottom);
/// did you mean \"top\"?" ("(none)" when there are none).
std::string known_names(const std::string& what, const std::string& name,
                        const std::vector<std::string>& known);
/// "unknown key 'x' in /path; did you mean 'y'?; known keys: a, b".
std::string unknown_key(const std::string& key, const std::string& where,
                        const std::vector<std::string>& known);

}  // namespace fe2
