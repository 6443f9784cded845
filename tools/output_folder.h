#pragma once
// The output folder (--out) of every command that writes one (run, circulation, study):
// each refuses the same way, before anything is written, a folder that holds an
// earlier output unless --overwrite (or, where offered, --resume) says what to do.
#include <string>
#include <vector>

namespace fe2::cli {

/// Whether the command offers --resume (go on with the earlier output) and was given it.
enum class Resume { not_offered, no, yes };

/// Refuses `dir` (InputError, naming it) if it exists and is not a folder, or if it holds
/// `earlier` (files of an earlier `what`, e.g. "an fe2heart run") and neither
/// `overwrite` nor --resume was given; the message names up to four of the files and
/// the flags. A missing or empty folder, or one with only other files, is fine.
/// Writes and removes nothing: the command replaces the earlier output as it writes.
void refuse_earlier_output(const std::string& dir, const std::string& what,
                           const std::vector<std::string>& earlier, bool overwrite,
                           Resume resume = Resume::not_offered);

/// The files of an earlier fe2heart run or circulation run in `dir` (RunOutput.h).
std::vector<std::string> earlier_run_files(const std::string& dir);

}  // namespace fe2::cli
