#pragma once
// The pictures `fe2heart run` draws from its summary.json with a Python script
// (pv_curve.png, pv_loop.png and pv_time.png). A picture is a convenience: when its
// script fails the run goes on, and the warning gives the script's own reason (its last
// line of output) instead of guessing, so that a failure for another reason than a
// missing matplotlib (e.g. an early-stopped run's summary) is not blamed on the install.
#include <string>

namespace fe2::cli {

/// Runs `/usr/bin/python3 SCRIPT RUN_DIR`; "" if it succeeded, else a warning naming
/// `pictures`, the command and the script's reason.
std::string run_plot_script(const std::string& script, const std::string& run_dir, const std::string& pictures);

}  // namespace fe2::cli
