#pragma once
// The spec reference printed by `fe2heart spec-doc` (--markdown: docs/spec-reference.md): one line per key of a schema
// (SchemaNode.h) with its type, default, the branch it belongs to and help. Shared
// definitions (<material>, <unit>) are printed once, after the specs that use them.
#include "common/spec/SchemaNode.h"

#include <string>
#include <utility>
#include <vector>

namespace fe2 {

/// `specs`: (heading, schema) pairs, printed in order, then their shared definitions;
/// as aligned text lines, or with `markdown` as one table per spec and definition
/// (docs/spec-reference.md).
std::string spec_reference(const std::vector<std::pair<std::string, const SchemaNode*>>& specs,
                           bool markdown = false);

}  // namespace fe2
