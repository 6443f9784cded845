#include "common/spec/memory_size.h"

#include "common/error.h"

#include <cmath>

namespace fe2 {

double parse_memory_size(const std::string& text, const std::string& what) {
  size_t used = 0;
  double value = -1;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = used ? text.substr(used) : "";
  double scale = 1;
  if (unit == "k" || unit == "K") scale = 1024.0;
  else if (unit == "M") scale = 1024.0 * 1024;
  else if (unit == "G") scale = 1024.0 * 1024 * 1024;
  else if (unit == "T") scale = 1024.0 * 1024 * 1024 * 1024;
  else if (!unit.empty()) used = 0;
  // The scaled size must be finite too: "1e308T" is no size (it once became +inf bytes).
  if (used == 0 || !std::isfinite(value) || value <= 0 || !std::isfinite(value * scale))
    throw InputError(fmt::format("{}: got '{}', expected a positive size in bytes, optionally "
                                 "with a suffix k, M, G or T (e.g. 8G, 500M)",
                                 what, text));
  return value * scale;
}

}  // namespace fe2
