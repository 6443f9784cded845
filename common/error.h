#pragma once
// One error vocabulary for fe2heart (after MFEM general/error.hpp):
//  - fe2::InputError: the user's spec, mesh or command line is wrong. The message
//    names the key or file, the value, and what was expected. Exit code 2.
//  - fe2::NumericalError: a solve failed (divergence, NaN, inverted element) in a
//    way the caller may recover from by cutting the step. Exit code 3 if uncaught.
//  - fe2::StallError: a peer rank stayed silent past farm.stall_timeout. Exit code 4.
//  - FE2_CHECK: an always-on internal invariant; message carries file:line and
//    function. FE2_ASSERT: the same, debug builds only.
#include <spdlog/fmt/fmt.h>

#include <stdexcept>
#include <string>

namespace fe2 {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual int exit_code() const { return 1; }
};

class InputError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return 2; }
};

class NumericalError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return 3; }
};

/// A rank waited longer than the liveness limit (farm.stall_timeout) for a message or
/// a collective: a peer is frozen, lost or far slower than allowed. Exit code 4.
class StallError : public Error {
 public:
  using Error::Error;
  int exit_code() const override { return 4; }
};

[[noreturn]] void fail_check(const char* expr, const char* file, int line,
                             const char* func, const std::string& msg);

}  // namespace fe2

#define FE2_CHECK(cond, ...)                                                      \
  do {                                                                            \
    if (!(cond))                                                                  \
      ::fe2::fail_check(#cond, __FILE__, __LINE__, __func__, fmt::format(__VA_ARGS__)); \
  } while (0)

#ifdef NDEBUG
#define FE2_ASSERT(cond, ...) ((void)0)
#else
#define FE2_ASSERT(cond, ...) FE2_CHECK(cond, __VA_ARGS__)
#endif
