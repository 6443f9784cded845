#pragma once
// Output files are written whole or not at all: content goes to `path.tmp`, which is
// then renamed over `path`, so a reader (ParaView, a script, a crash) never sees a
// partial file. Log lines are appended whole (append_line).
#include <string_view>
#include <string>

namespace fe2 {

/// Throws InputError if the folder is not writable, Error on a failed write or rename.
void write_file_atomically(const std::string& path, std::string_view content);

/// Appends `line` (a newline is added) to `path`, creating the file but not its folder,
/// in one write() on a file opened with O_APPEND: lines that several processes append
/// to the same file (every rank's fatal error into one log) never interleave. Best
/// effort, for last words on an error path: returns false instead of throwing.
bool append_line(const std::string& path, std::string_view line) noexcept;

}  // namespace fe2
