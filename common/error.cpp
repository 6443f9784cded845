#include "common/error.h"

namespace fe2 {

void fail_check(const char* expr, const char* file, int line, const char* func,
                const std::string& msg) {
  throw Error(fmt::format("internal check failed: {} ({}:{} in {}): {}", expr, file, line,
                          func, msg));
}

}  // namespace fe2
