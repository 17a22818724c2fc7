// Writing the commands' results (see output.hpp).
#include "cli/output.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <CLI/CLI.hpp>

#include "fremond/core/error.hpp"

namespace fremond::cli {

void write_atomically(const std::filesystem::path& dir, const std::string& name,
                      const std::string& text) {
  std::string tmpl = (dir / ("." + name + ".XXXXXX")).string();
  const int fd = mkstemp(tmpl.data());
  if (fd < 0)
    throw InvalidArgument((dir / name).string(),
                          std::string("cannot write: ") + std::strerror(errno));
  // mkstemp makes the file private; give it the permissions of an ordinary new file.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  std::size_t off = 0;
  bool ok = true;
  while (ok && off < text.size()) {
    const ssize_t w = ::write(fd, text.data() + off, text.size() - off);
    if (w < 0 && errno == EINTR) continue;
    ok = w > 0;
    if (ok) off += static_cast<std::size_t>(w);
  }
  const int err = ok ? 0 : errno;
  ok = ok && ::fsync(fd) == 0;
  ok = (::close(fd) == 0) && ok;
  if (ok && std::rename(tmpl.c_str(), (dir / name).c_str()) == 0) return;
  const int e = err ? err : errno;
  std::remove(tmpl.c_str());
  throw InvalidArgument((dir / name).string(), std::string("cannot write: ") + std::strerror(e));
}

bool write_stdout(const std::string& text) {
  errno = 0;
  return std::fwrite(text.data(), 1, text.size(), stdout) == text.size() &&
         std::fflush(stdout) == 0;
}

std::string number17(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string brief(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void exit_with(int code) {
  throw CLI::RuntimeError(code);
}

}  // namespace fremond::cli
