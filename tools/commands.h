#pragma once
// The fe2heart subcommands; each returns the process exit code.
#include <string>

namespace fe2::cli {

struct RunOptions {
  std::string spec;
  std::string out;
  int coordinators = 0;  ///< 0: from the spec
};
int run(const RunOptions& o);
int validate(const std::string& spec);

struct UnitOptions {
  std::string spec;
  std::string vtu;  ///< optional: write the equilibrated unit mesh here
};
int unit(const UnitOptions& o);

struct BenchOptions {
  int dofs = 26000;
  int repeat = 5;
  std::string cell = "two_cells";
  double stale_stretch = 0.002;  ///< how far Z̄ moves from the factored state
};
int bench_unit(const BenchOptions& o);

}  // namespace fe2::cli
