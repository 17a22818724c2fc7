#pragma once
// Writing the commands' results (files are complete or absent, standard output is checked), and
// ending a command with its exit status.
#include <filesystem>
#include <string>

namespace fremond::cli {

/// Writes `text` to DIR/name through a temporary file in DIR and a rename, so that the file is
/// either absent or complete, never half-written. Throws InvalidArgument naming the file.
void write_atomically(const std::filesystem::path& dir, const std::string& name,
                      const std::string& text);

/// Writes `text` to standard output and flushes; false when it could not be written in full
/// (a full disk, a closed pipe, a size limit), so the caller can exit non-zero.
bool write_stdout(const std::string& text);

/// A number as text with %.17g, which reads back to the same double.
std::string number17(double v);

/// A number as text with %.6g, for messages.
std::string brief(double v);

/// Ends the command with exit status `code` (through CLI11, which unwinds to main).
[[noreturn]] void exit_with(int code);

}  // namespace fremond::cli
