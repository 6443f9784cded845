#pragma once
// A request to stop a run (a batch system's SIGTERM or SIGUSR1, a user's Ctrl-C,
// SIGINT): `fe2heart run` stops within one Newton iteration, even in the middle of a
// step that keeps cutting back, writes a checkpoint of the committed state and exits 0. The handler is installed before
// MPI_Init, so a rank that is still starting up (reading its spec, building units) when
// the request comes is not killed by it: it records the request like every other rank.

#include <string>

namespace fe2::cli {

/// From now on SIGTERM, SIGINT and SIGUSR1 are recorded, not acted on.
void catch_stop_signals();
/// The last stop signal recorded, or 0.
int stop_signal();
/// What stop_request() answers when the stop file exists (above every signal number).
inline constexpr int kStopFileFound = 1000;
/// From now on stop_request() also answers kStopFileFound once `path` exists (`run
/// --stop-file`; empty: no file). A file, unlike a signal, cannot be lost: one that comes
/// before a rank has its handlers (mpirun forwarding SIGUSR1 to a rank between its exec
/// and main) kills it; the file waits until the run looks.
void watch_stop_file(std::string path);
/// stop_signal(), or else kStopFileFound if the watched stop file exists, or else 0.
int stop_request();
/// Back to the default actions (for every subcommand but `run`); a stop signal recorded
/// meanwhile is raised again now, so it acts as it would have.
void release_stop_signals();

}  // namespace fe2::cli
