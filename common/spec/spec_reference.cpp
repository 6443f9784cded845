#include "common/spec/spec_reference.h"

#include <map>

namespace fe2 {

namespace {

class Printer {
 public:
  std::string out;

  void spec(const std::string& heading, const SchemaNode& root) {
    out += heading + "\n";
    walk("", root, "");
    out += "\n";
  }

  /// Prints every definition met so far (and those they use), each once.
  void definitions() {
    for (size_t i = 0; i < defs_.size(); ++i) {
      const SchemaNode& d = *defs_[i];
      out += fmt::format("<{}>: {} (at {})\n", d.definition, d.help,
                         fmt::join(used_at_[d.definition], ", "));
      children("<" + d.definition + ">", d);
      out += "\n";
    }
  }

 private:
  void row(const std::string& path, const SchemaNode& n, const std::string& when) {
    out += fmt::format("  {:<42} {} ({}){}: {}\n", path, n.type_text(), n.default_text(),
                       when.empty() ? "" : ", when " + when, n.help);
  }

  void walk(const std::string& path, const SchemaNode& n, const std::string& when) {
    if (!path.empty()) row(path, n, when);
    if (!n.definition.empty()) {
      if (!used_at_.count(n.definition)) defs_.push_back(&n);
      used_at_[n.definition].push_back(path);
      return;
    }
    children(path, n);
  }

  void children(const std::string& path, const SchemaNode& n) {
    using T = SchemaNode::Type;
    if (n.type == T::object) {
      if (!n.exactly_one_of.empty())
        out += fmt::format("  {:<42} exactly one of: {}\n", path.empty() ? "/" : path,
                           fmt::join(n.exactly_one_of, ", "));
      for (const auto& [key, k] : n.keys) walk(path + "/" + key, *k, "");
      for (const auto& b : n.branches)
        for (const auto& [key, k] : b.keys)
          walk(path + "/" + key, *k, fmt::format("{} = \"{}\"", n.discriminator, b.value));
    } else if (n.type == T::map) {
      walk(path + "/<" + n.entry_name + ">", *n.element, "");
    } else if (n.type == T::array) {
      walk(path + "/<i>", *n.element, "");
    } else if (n.type == T::custom) {
      // A custom type's object form (e.g. a number or {fibre, sheet, normal}): a line
      // per property, so every key a user may write is listed.
      custom_properties(path, n.custom_schema);
    }
  }

  void custom_properties(const std::string& path, const json& s) {
    if (s.is_array())
      for (const auto& sub : s) custom_properties(path, sub);
    if (!s.is_object()) return;
    if (s.contains("properties"))
      for (auto it = s["properties"].begin(); it != s["properties"].end(); ++it)
        out += fmt::format("  {:<42} {}: in the object form of {}\n", path + "/" + it.key(),
                           it.value().value("type", std::string("value")), path);
    for (const char* alt : {"oneOf", "anyOf"})
      if (s.contains(alt)) custom_properties(path, s[alt]);
  }

  std::vector<const SchemaNode*> defs_;
  std::map<std::string, std::vector<std::string>> used_at_;
};

}  // namespace

std::string spec_reference(const std::vector<std::pair<std::string, const SchemaNode*>>& specs) {
  Printer p;
  for (const auto& [heading, root] : specs) p.spec(heading, *root);
  p.definitions();
  return p.out;
}

}  // namespace fe2
