#pragma once
// Output files are written whole or not at all: content goes to `path.tmp`, which is
// then renamed over `path`, so a reader (ParaView, a script, a crash) never sees a
// partial file.
#include <string_view>
#include <string>

namespace fe2 {

/// Throws InputError if the folder is not writable, Error on a failed write or rename.
void write_file_atomically(const std::string& path, std::string_view content);

}  // namespace fe2
