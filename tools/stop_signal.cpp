#include "tools/stop_signal.h"

#include <csignal>
#include <filesystem>
#include <utility>

namespace fe2::cli {

namespace {
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int signal) { g_stop_signal = signal; }
std::string g_stop_file;
}  // namespace

void catch_stop_signals() {
  std::signal(SIGTERM, on_stop_signal);
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGUSR1, on_stop_signal);
}

int stop_signal() { return g_stop_signal; }

void watch_stop_file(std::string path) { g_stop_file = std::move(path); }

int stop_request() {
  if (g_stop_signal != 0) return g_stop_signal;
  std::error_code ec;  // an unreadable folder is no request
  return !g_stop_file.empty() && std::filesystem::exists(g_stop_file, ec) ? kStopFileFound : 0;
}

void release_stop_signals() {
  std::signal(SIGTERM, SIG_DFL);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGUSR1, SIG_DFL);
  if (g_stop_signal != 0) std::raise(g_stop_signal);
}

}  // namespace fe2::cli
