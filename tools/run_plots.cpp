#include "tools/run_plots.h"

#include <spdlog/fmt/fmt.h>

#include <array>
#include <cstdio>
#include <sys/wait.h>

namespace fe2::cli {

std::string run_plot_script(const std::string& script, const std::string& run_dir, const std::string& pictures) {
  const std::string cmd = fmt::format("/usr/bin/python3 '{}' '{}'", script, run_dir);
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  if (!pipe) return fmt::format("no {}: could not start '{}'", pictures, cmd);
  std::string output;
  std::array<char, 512> chunk{};
  while (fgets(chunk.data(), static_cast<int>(chunk.size()), pipe)) output += chunk.data();
  const int status = pclose(pipe);
  if (status == 0) return "";
  // The script's last non-empty line: a Python traceback ends with the exception.
  while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) output.pop_back();
  const std::string last = output.substr(output.find_last_of('\n') == std::string::npos ? 0 : output.find_last_of('\n') + 1);
  const bool no_matplotlib = output.find("No module named 'matplotlib'") != std::string::npos;
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (no_matplotlib) return fmt::format("no {}: '{}' needs Debian's python3-matplotlib ({})", pictures, cmd, last);
  return fmt::format("no {}: '{}' failed (exit {}): {}", pictures, cmd, code, last.empty() ? "no output" : last);
}

}  // namespace fe2::cli
