#include "common/spec/SpecNode.h"

#include "common/spec/SchemaNode.h"

#include <algorithm>
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

const json& SpecNode::empty_object() {
  static const json e = json::object();
  return e;
}

SpecNode::SpecNode(const json& j, std::string path, SpecDoc* doc, const SchemaNode* schema)
    : j_(&j), path_(std::move(path)), doc_(doc), schema_(schema) {
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

const SchemaNode* SpecNode::declare(const std::string& key,
                                    const std::shared_ptr<const SchemaNode>& reader) {
  declared_.push_back(key);
  if (!schema_) return nullptr;
  const SchemaNode* s = schema_->find(key, *j_);
  const std::string why =
      s ? s->disagreement(*reader)
        : "the reader declares " + reader->type_text() + ", " + reader->default_text() +
              ", the schema has no such key here";
  if (!why.empty())
    throw Error(fmt::format("internal error: the spec reader and the spec schema "
                            "(common/spec/spec_schemas.cpp) disagree on {}: {}",
                            key_path(key), why));
  if (doc_) doc_->visited.insert(s);
  return s;
}

void SpecNode::fail(const std::string& key, const std::string& expected) const {
  const json* v = lookup(key);
  throw InputError(fmt::format("{}: got {}, expected {}", key_path(key),
                               v ? show(*v) : std::string("nothing (key missing)"), expected));
}

double SpecNode::number(const std::string& key, std::optional<double> def, Range range,
                        const std::string& help) {
  declare(key, schema::number(def, range, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, "a number " + range.describe() + " (" + help + ")");
    return *def;
  }
  if (!v->is_number()) fail(key, "a number " + range.describe() + " (" + help + ")");
  const double x = v->get<double>();
  if (!range.contains(x)) fail(key, "a number " + range.describe() + " (" + help + ")");
  return x;
}

int SpecNode::integer(const std::string& key, std::optional<int> def, Range range,
                      const std::string& help) {
  declare(key, schema::integer(def, range, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, "an integer " + range.describe() + " (" + help + ")");
    return *def;
  }
  if (!v->is_number_integer() || !range.contains(v->get<double>()))
    fail(key, "an integer " + range.describe() + " (" + help + ")");
  return v->get<int>();
}

bool SpecNode::boolean(const std::string& key, std::optional<bool> def, const std::string& help) {
  declare(key, schema::boolean(def, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, "true or false (" + help + ")");
    return *def;
  }
  if (!v->is_boolean()) fail(key, "true or false (" + help + ")");
  return v->get<bool>();
}

std::string SpecNode::string(const std::string& key, std::optional<std::string> def,
                             const std::string& help) {
  declare(key, schema::string(def, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, "a string (" + help + ")");
    return *def;
  }
  if (!v->is_string()) fail(key, "a string (" + help + ")");
  return v->get<std::string>();
}

std::string SpecNode::choice(const std::string& key, std::optional<std::string> def,
                             const std::vector<std::string>& choices, const std::string& help) {
  const std::string allowed = "one of \"" + join(choices, "\", \"") + "\"";
  declare(key, schema::choice(def, choices, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, allowed + " (" + help + ")");
    return *def;
  }
  if (!v->is_string()) fail(key, allowed);
  const std::string s = v->get<std::string>();
  if (std::find(choices.begin(), choices.end(), s) == choices.end()) {
    const std::string guess = closest_match(s, choices);
    fail(key, allowed + (guess.empty() ? "" : "; did you mean \"" + guess + "\"?"));
  }
  return s;
}

std::vector<double> SpecNode::numbers(const std::string& key, int size,
                                      std::optional<std::vector<double>> def,
                                      const std::string& help) {
  const std::string what =
      size >= 0 ? fmt::format("an array of {} numbers", size) : "a non-empty array of numbers";
  declare(key, schema::numbers(size, def, help));
  const json* v = lookup(key);
  if (!v) {
    if (!def) fail(key, what + " (" + help + ")");
    return *def;
  }
  if (!v->is_array() || (size >= 0 && static_cast<int>(v->size()) != size) || v->empty())
    fail(key, what + " (" + help + ")");
  std::vector<double> out;
  for (const auto& x : *v) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) fail(key, what + " (" + help + ")");
    out.push_back(x.get<double>());
  }
  return out;
}

SpecNode SpecNode::child(const std::string& key, bool required, const std::string& help) {
  const SchemaNode* s = declare(key, schema::object(required, help, {}));
  const json* v = lookup(key);
  if (!v) {
    if (required) fail(key, "an object (" + help + ")");
    return SpecNode(empty_object(), key_path(key), doc_, s);
  }
  if (!v->is_object()) fail(key, "an object (" + help + ")");
  return SpecNode(*v, key_path(key), doc_, s);
}

std::vector<std::string> SpecNode::names(const std::string& key, const std::string& help) const {
  const_cast<SpecNode*>(this)->declare(
      key, schema::map(false, help, "name", schema::custom("any", "", json::object())));
  std::vector<std::string> out;
  const json* v = lookup(key);
  if (!v) return out;
  if (!v->is_object()) fail(key, "an object of named entries (" + help + ")");
  for (auto it = v->begin(); it != v->end(); ++it) out.push_back(it.key());
  return out;
}

std::vector<SpecNode> SpecNode::children(const std::string& key, bool required,
                                         const std::string& help) {
  const SchemaNode* s = declare(key, schema::array(required, help, schema::object(true, "", {})));
  const SchemaNode* item = s ? s->element.get() : nullptr;
  std::vector<SpecNode> out;
  const json* v = lookup(key);
  if (!v) {
    if (required) fail(key, "an array of objects (" + help + ")");
    return out;
  }
  if (!v->is_array()) fail(key, "an array of objects (" + help + ")");
  if (doc_ && item && !v->empty()) doc_->visited.insert(item);
  for (size_t i = 0; i < v->size(); ++i)
    out.emplace_back((*v)[i], key_path(key) + "/" + std::to_string(i), doc_, item);
  return out;
}

const json* SpecNode::declared_value(const std::string& key, const std::string& type,
                                     const std::string& help) {
  declare(key, schema::custom(type, help, json::object()));
  return lookup(key);
}

void SpecNode::finish() const {
  for (auto it = j_->begin(); it != j_->end(); ++it) {
    if (std::find(declared_.begin(), declared_.end(), it.key()) != declared_.end()) continue;
    const std::string guess = closest_match(it.key(), declared_);
    throw InputError(fmt::format("unknown key '{}' in {}{}; known keys: {}", it.key(),
                                 path_.empty() ? "/" : path_,
                                 guess.empty() ? "" : "; did you mean '" + guess + "'?",
                                 join(declared_, ", ")));
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
