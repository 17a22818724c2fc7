#pragma once
/// @file The one exception type of the library: bad input, naming the offending value and the
/// reason.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace fremond {

/// Thrown when a caller hands the library something that is not a valid problem, law, potential or
/// option. The message always names the argument (or file key) and the reason, e.g.
/// `law.normal.p: must be > 1, got 0.5`.
class InvalidArgument : public std::invalid_argument {
 public:
  InvalidArgument(const std::string& what_name, const std::string& reason)
      : std::invalid_argument(printable(what_name) + ": " + printable(reason)),
        name_(printable(what_name)) {}
  /// The argument or key that was refused.
  const std::string& name() const noexcept { return name_; }

  /// `text` with its control characters written as \u00XX: a key or value read from a file may
  /// hold any of them (JSON allows "\u0000"), and a NUL would cut what() short, others reach the
  /// user's terminal raw.
  static std::string printable(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char ch : text) {
      const auto u = static_cast<unsigned char>(ch);
      if (u < 0x20 && ch != '\n' && ch != '\t') {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", u);
        out += buf;
      } else if (u == 0x7f) {
        out += "\\u007f";
      } else {
        out += ch;
      }
    }
    return out;
  }

 private:
  std::string name_;
};

}  // namespace fremond
