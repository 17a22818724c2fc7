#include "cli/measured_input.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include "cli/output.hpp"
#include "fremond/core/error.hpp"
#include "fremond/io/measurements.hpp"

namespace fremond::cli {

std::vector<MeasuredImpact> read_measured(const std::string& file) {
  if (file == "-") return io::read_measurements(std::cin);
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InvalidArgument(file, "is a directory, not a measured-impact file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InvalidArgument(file, std::string("cannot open: ") + std::strerror(errno));
  return io::read_measurements(in);
}

std::map<std::string, double> named_values(const std::vector<std::string>& items,
                                           const std::string& option) {
  std::map<std::string, double> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InvalidArgument(option, "expects NAME=VALUE, got '" + item + "'");
    const std::string name = item.substr(0, eq), text = item.substr(eq + 1);
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw InvalidArgument(
          option, "the value of " + name + " must be a finite number, got '" + text + "'");
    if (out.count(name)) throw InvalidArgument(option, name + " is given twice");
    out[name] = v;
  }
  return out;
}

void write_text(const std::string& out, const std::string& text) {
  if (out.empty()) {
    if (!write_stdout(text))
      throw InvalidArgument("standard output", std::string("cannot write: ") +
                                                   (errno ? std::strerror(errno) : "write failed"));
    return;
  }
  const std::filesystem::path path(out);
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
  try {
    write_atomically(dir, path.filename().string(), text);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--out", e.what());
  }
}

}  // namespace fremond::cli
