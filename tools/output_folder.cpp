#include "tools/output_folder.h"

#include "common/error.h"
#include "coordinator/output/RunOutput.h"

#include <filesystem>

namespace fe2::cli {

void refuse_earlier_output(const std::string& dir, const std::string& what,
                           const std::vector<std::string>& earlier, bool overwrite, Resume resume) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw InputError(fmt::format("--out '{}' exists and is not a folder; expected a folder for {}'s output "
                                 "(new, empty, or an earlier one with --overwrite)",
                                 dir, what));
  if (earlier.empty() || overwrite || resume == Resume::yes) return;
  const std::size_t shown = std::min<std::size_t>(earlier.size(), 4);
  throw InputError(fmt::format(
      "--out '{}' already holds {} ({} file{}: {}{}); use {}--overwrite to replace it, or another --out", dir,
      what, earlier.size(), earlier.size() == 1 ? "" : "s",
      fmt::join(earlier.begin(), earlier.begin() + static_cast<std::ptrdiff_t>(shown), ", "),
      earlier.size() > shown ? ", ..." : "", resume == Resume::no ? "--resume to go on with it, " : ""));
}

std::vector<std::string> earlier_run_files(const std::string& dir) { return run_output_files(dir); }

}  // namespace fe2::cli
