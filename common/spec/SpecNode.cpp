#include "common/spec/SpecNode.h"

#include "common/spec/SchemaNode.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace fe2 {

namespace {

std::string show(const json& v) {
  std::string s = v.dump();
  return s.size() > 80 ? s.substr(0, 77) + "..." : s;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  const bool lo_ok = lo_open ? v > lo : v >= lo;
  const bool hi_ok = hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return fmt::format("in {}{}, {}{}", lo_open ? "(" : "[", lo, hi, hi_open ? ")" : "]");
  if (has_lo) return fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  if (has_hi) return fmt::format("{} {}", hi_open ? "<" : "<=", hi);
  return "finite";
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = std::max<size_t>(2, word.size() / 3) + 1;
  for (const auto& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known, char quote) {
  // A number (a region tag) is not misspelt: the nearest digits would be a guess.
  if (!name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isdigit(c); }))
    return "";
  const std::string guess = closest_match(name, known);
  return guess.empty() ? "" : fmt::format("; did you mean {}{}{}?", quote, guess, quote);
}

std::string known_names(const std::string& what, const std::string& name,
                        const std::vector<std::string>& known) {
  return fmt::format("{} ({}){}", what, known.empty() ? std::string("none") : join(known, ", "),
                     did_you_mean(name, known));
}

std::string unknown_key(const std::string& key, const std::string& where,
                        const std::vector<std::string>& known) {
  return fmt::format("unknown key '{}' in {}{}; known keys: {}", key, where.empty() ? "/" : where,
                     did_you_mean(key, known, '\''), join(known, ", "));
}

const json& SpecNode::empty_object() {
  static const json e = json::object();
  return e;
}

SpecNode::SpecNode(const json& j, std::string path, const SchemaNode& schema, SpecDoc* doc)
    : j_(&j), path_(std::move(path)), doc_(doc), schema_(&schema) {
  if (!j.is_object())
    throw InputError(fmt::format("{}: got {}, expected an object", path_.empty() ? "/" : path_,
                                 show(j)));
}

std::string SpecNode::key_path(const std::string& key) const { return path_ + "/" + key; }

bool SpecNode::has(const std::string& key) const { return j_->contains(key); }

const json* SpecNode::lookup(const std::string& key) const {
  auto it = j_->find(key);
  return it == j_->end() ? nullptr : &*it;
}

namespace {

using Type = SchemaNode::Type;

/// Whether the accessor `reader` reads a value of schema type `t`.
bool reads(const char* reader, Type t) {
  const std::string r = reader;
  if (r == "child") return t == Type::object || t == Type::map;
  if (r == "children") return t == Type::array;
  if (r == "declared_value") return t == Type::custom;
  static const std::map<std::string, Type> scalar = {
      {"number", Type::number}, {"integer", Type::integer}, {"boolean", Type::boolean},
      {"string", Type::string}, {"choice", Type::choice},   {"numbers", Type::numbers}};
  const auto it = scalar.find(r);
  return it != scalar.end() && it->second == t;
}

/// What a key of schema `s` must hold, in the schema's words: "a number > 0 (end time)".
std::string expected_of(const SchemaNode& s) {
  std::string what;
  switch (s.type) {
    case Type::number: what = "a number " + s.range.describe(); break;
    case Type::integer: what = "an integer " + s.range.describe(); break;
    case Type::boolean: what = "true or false"; break;
    case Type::string: what = "a string"; break;
    case Type::choice: what = "one of \"" + join(s.choices, "\", \"") + "\""; break;
    case Type::numbers: what = (s.size >= 0 ? "an " : "a ") + s.type_text(); break;
    case Type::object: what = "an object"; break;
    case Type::map: what = "an object of named entries"; break;
    case Type::array: what = "an array of objects"; break;
    case Type::custom: what = s.custom_type; break;
  }
  return s.help.empty() ? what : what + " (" + s.help + ")";
}

}  // namespace

const SchemaNode& SpecNode::schema_of(const std::string& key, const char* reader) const {
  const SchemaNode* s = schema_->find(key, *j_);
  if (!s)
    throw Error(fmt::format("internal error: the spec reader reads {} ({}), which the spec schema "
                            "(common/spec/spec_schemas.cpp) has no key for here",
                            key_path(key), reader));
  if (!reads(reader, s->type))
    throw Error(fmt::format("internal error: the spec reader reads {} with {}(), the spec schema "
                            "(common/spec/spec_schemas.cpp) declares it {}",
                            key_path(key), reader, s->type_text()));
  return *s;
}

const SchemaNode& SpecNode::declare(const std::string& key, const char* reader) {
  const SchemaNode& s = schema_of(key, reader);
  declared_.push_back(key);
  if (doc_) doc_->visited.insert(&s);
  return s;
}

std::string SpecNode::expected(const std::string& key) const {
  const SchemaNode* s = schema_->find(key, *j_);
  return s ? expected_of(*s) : std::string("no such key");
}

void SpecNode::fail(const std::string& key, const std::string& expected) const {
  const json* v = lookup(key);
  throw InputError(fmt::format("{}: got {}, expected {}", key_path(key),
                               v ? show(*v) : std::string("nothing (key missing)"), expected));
}

namespace {

/// The value of `key`, or its schema default (a required or default-less key that is
/// absent fails).
template <class T>
T absent_default(const SpecNode& node, const std::string& key, const SchemaNode& s) {
  if (!s.def) node.fail(key, expected_of(s));
  return s.def->get<T>();
}

}  // namespace

double SpecNode::number(const std::string& key) {
  const SchemaNode& s = declare(key, "number");
  const json* v = lookup(key);
  if (!v) return absent_default<double>(*this, key, s);
  if (!v->is_number() || !s.range.contains(v->get<double>())) fail(key, expected_of(s));
  return v->get<double>();
}

int SpecNode::integer(const std::string& key) {
  const SchemaNode& s = declare(key, "integer");
  const json* v = lookup(key);
  if (!v) return absent_default<int>(*this, key, s);
  if (!v->is_number_integer() || !s.range.contains(v->get<double>())) fail(key, expected_of(s));
  return v->get<int>();
}

bool SpecNode::boolean(const std::string& key) {
  const SchemaNode& s = declare(key, "boolean");
  const json* v = lookup(key);
  if (!v) return absent_default<bool>(*this, key, s);
  if (!v->is_boolean()) fail(key, expected_of(s));
  return v->get<bool>();
}

std::string SpecNode::string(const std::string& key) {
  const SchemaNode& s = declare(key, "string");
  const json* v = lookup(key);
  if (!v) return absent_default<std::string>(*this, key, s);
  if (!v->is_string()) fail(key, expected_of(s));
  return v->get<std::string>();
}

std::string SpecNode::choice(const std::string& key) {
  const SchemaNode& s = declare(key, "choice");
  const json* v = lookup(key);
  if (!v) return absent_default<std::string>(*this, key, s);
  if (!v->is_string()) fail(key, expected_of(s));
  const std::string c = v->get<std::string>();
  if (std::find(s.choices.begin(), s.choices.end(), c) == s.choices.end())
    fail(key, expected_of(s) + did_you_mean(c, s.choices));
  return c;
}

std::vector<double> SpecNode::numbers(const std::string& key) {
  const SchemaNode& s = declare(key, "numbers");
  const json* v = lookup(key);
  if (!v) return absent_default<std::vector<double>>(*this, key, s);
  if (!v->is_array() || (s.size >= 0 && static_cast<int>(v->size()) != s.size) || v->empty())
    fail(key, expected_of(s));
  std::vector<double> out;
  for (const auto& x : *v) {
    const bool ok = x.is_number() && std::isfinite(x.get<double>()) &&
                    s.range.contains(x.get<double>()) &&
                    (!s.integer_items || x.get<double>() == std::floor(x.get<double>()));
    if (!ok) fail(key, expected_of(s));
    out.push_back(x.get<double>());
  }
  return out;
}

SpecNode SpecNode::child(const std::string& key) {
  const SchemaNode& s = declare(key, "child");
  const json* v = lookup(key);
  if (!v) {
    if (s.required) fail(key, expected_of(s));
    return SpecNode(empty_object(), key_path(key), s, doc_);
  }
  if (!v->is_object()) fail(key, expected_of(s));
  return SpecNode(*v, key_path(key), s, doc_);
}

std::vector<SpecNode> SpecNode::children(const std::string& key) {
  const SchemaNode& s = declare(key, "children");
  const SchemaNode& item = *s.element;
  std::vector<SpecNode> out;
  const json* v = lookup(key);
  if (!v) {
    if (s.required) fail(key, expected_of(s));
    return out;
  }
  if (!v->is_array()) fail(key, expected_of(s));
  if (doc_ && !v->empty()) doc_->visited.insert(&item);
  for (size_t i = 0; i < v->size(); ++i)
    out.emplace_back((*v)[i], key_path(key) + "/" + std::to_string(i), item, doc_);
  return out;
}

const json* SpecNode::declared_value(const std::string& key) {
  const SchemaNode& s = declare(key, "declared_value");
  const json* v = lookup(key);
  if (!v && s.required) fail(key, expected_of(s));
  return v;
}

void SpecNode::finish() const {
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    if (std::find(declared_.begin(), declared_.end(), it.key()) != declared_.end()) continue;
    // The schema's keys, not only those read: a key read only when present (an
    // override) is still suggested for a misspelling of it.
    std::vector<std::string> known = schema_->key_names(*j_);
    for (const auto& d : declared_)
      if (std::find(known.begin(), known.end(), d) == known.end()) known.push_back(d);
    throw InputError(unknown_key(it.key(), path_, known));
  }
}

namespace {

// Deeper specs are refused before they are built: nlohmann's parser is iterative, but a
// value nested 70,000 deep still crashed while being reported. No real spec nests past ~6.
constexpr int kMaxSpecDepth = 64;

// Follows the parser's events to know where it is (a JSON pointer such as
// /models/muscle/unit) and which keys each open object already has: nlohmann keeps the
// last of two equal keys silently, and a parse error names no key.
class JsonPathTracker {
 public:
  explicit JsonPathTracker(std::string file) : file_(std::move(file)) {}

  bool operator()(int depth, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    switch (event) {
      case E::object_start:
      case E::array_start:
        if (depth + 1 > kMaxSpecDepth)  // depth counts the containers around this one
          throw InputError(fmt::format(
              "spec file '{}': nesting depth {} at {} exceeds the limit of {}, expected a spec "
              "nested at most {} deep",
              file_, depth + 1, pointer(), kMaxSpecDepth, kMaxSpecDepth));
        frames_.push_back({event == E::array_start, "", 0, {}});
        break;
      case E::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw InputError(fmt::format("spec file '{}': duplicate key '{}' at {}, expected each "
                                       "key once per object",
                                       file_, f.key, pointer()));
        break;
      }
      case E::object_end:
      case E::array_end:
        frames_.pop_back();
        next_element();
        break;
      case E::value:
        next_element();
        break;
    }
    return true;
  }

  /// Where the parser is: "/a/b/3", or "/" at the top.
  std::string pointer() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array) p += "/" + std::to_string(f.index);
      else if (!f.keys.empty()) p += "/" + f.key;
    }
    return p.empty() ? "/" : p;
  }

 private:
  struct Frame {
    bool array = false;
    std::string key;   ///< object: the key being read
    size_t index = 0;  ///< array: the element being read
    std::set<std::string> keys;
  };
  void next_element() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

namespace {

// The one parse of spec text (files and the fuzz target tests/fuzz/fuzz_spec.cpp).
template <class Parse>
json parse_spec(const std::string& file, Parse&& parse) {
  JsonPathTracker where(file);
  try {
    return parse(std::ref(where));
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("spec file '{}' is not valid JSON: {}", file, e.what()));
  } catch (const json::exception& e) {  // e.g. out_of_range 406: a number such as 1e999
    throw InputError(fmt::format("spec file '{}' at {}: {}, expected a finite JSON value", file,
                                 where.pointer(), e.what()));
  }
}

}  // namespace

json parse_json_text(std::string_view text, const std::string& file) {
  return parse_spec(file, [&](auto cb) { return json::parse(text.begin(), text.end(), cb); });
}

json read_json_file(const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(fmt::format("spec file '{}' is a directory, expected a JSON file", file));
  std::ifstream in(file);
  if (!in)
    throw InputError(fmt::format("cannot open spec file '{}' ({})", file, std::strerror(errno)));
  return parse_spec(file, [&](auto cb) { return json::parse(in, cb); });
}

}  // namespace fe2
