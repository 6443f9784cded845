#pragma once
// A memory size as users write it: "8G", "500M", "64k", "1.5G" (powers of 1024) or
// "123456" (bytes). Shared by `--memory-limit` and the spec key farm.factor_memory_budget.
#include <string>

namespace fe2 {

/// Bytes of `text`. Throws InputError naming `what` (an option or a spec key path) and
/// the text when it is not a positive size.
double parse_memory_size(const std::string& text, const std::string& what);

}  // namespace fe2
