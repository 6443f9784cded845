#include "common/spec/spec_reference.h"

#include <map>

namespace fe2 {

namespace {

/// Markdown table cell text: "|" would end the cell, "<name>" would be read as HTML.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += "\\|";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

class Printer {
 public:
  explicit Printer(bool markdown) : md_(markdown) {}
  std::string out;

  void spec(const std::string& heading, const SchemaNode& root) {
    section(md_ ? "## " + heading : heading);
    walk("", root, "");
    out += "\n";
  }

  /// Prints every definition met so far (and those they use), each once.
  void definitions() {
    if (md_ && !defs_.empty())
      out += "## Shared definitions\n\nObjects used in several places, each listed once.\n\n";
    for (size_t i = 0; i < defs_.size(); ++i) {
      const SchemaNode& d = *defs_[i];
      const auto& at = used_at_[d.definition];
      if (md_)
        section(fmt::format("### `<{}>`\n\n{} (at `{}`)\n", d.definition, cell(d.help), fmt::join(at, "`, `")));
      else
        out += fmt::format("<{}>: {} (at {})\n", d.definition, d.help, fmt::join(at, ", "));
      children("<" + d.definition + ">", d);
      out += "\n";
    }
  }

 private:
  /// A heading, and in markdown the header of its table.
  void section(const std::string& heading) {
    out += heading + "\n";
    if (md_) out += "\n| Key | Type | Default | When | Help |\n|---|---|---|---|---|\n";
  }

  /// One line (text) or table row (markdown): the key, its type, default, branch, help.
  void entry(const std::string& path, const std::string& type, const std::string& def,
             const std::string& when, const std::string& help) {
    if (md_) {
      out += fmt::format("| `{}` | {} | {} | {} | {} |\n", path, cell(type), cell(def), cell(when), cell(help));
      return;
    }
    out += fmt::format("  {:<42} {}{}{}{}\n", path, type, def.empty() ? "" : " (" + def + ")",
                       when.empty() ? "" : ", when " + when, help.empty() ? "" : ": " + help);
  }

  void row(const std::string& path, const SchemaNode& n, const std::string& when) {
    entry(path, n.type_text(), n.default_text(), when, n.help);
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
        entry(path.empty() ? "/" : path, fmt::format("exactly one of: {}", fmt::join(n.exactly_one_of, ", ")),
              "", "", "");
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
        entry(path + "/" + it.key(), it.value().value("type", std::string("value")), "", "",
              "in the object form of " + path);
    for (const char* alt : {"oneOf", "anyOf"})
      if (s.contains(alt)) custom_properties(path, s[alt]);
  }

  bool md_;
  std::vector<const SchemaNode*> defs_;
  std::map<std::string, std::vector<std::string>> used_at_;
};

}  // namespace

std::string spec_reference(const std::vector<std::pair<std::string, const SchemaNode*>>& specs,
                           bool markdown) {
  Printer p(markdown);
  for (const auto& [heading, root] : specs) p.spec(heading, *root);
  p.definitions();
  return p.out;
}

}  // namespace fe2
