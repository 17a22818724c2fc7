#pragma once
/// @file The one exception type of the library: bad input, naming the offending value and the reason.
#include <stdexcept>
#include <string>

namespace fremond {

/// Thrown when a caller hands the library something that is not a valid problem, law, potential or
/// option. The message always names the argument (or file key) and the reason, e.g.
/// `law.normal.p: must be > 1, got 0.5`.
class InvalidArgument : public std::invalid_argument {
 public:
  InvalidArgument(const std::string& what_name, const std::string& reason)
      : std::invalid_argument(what_name + ": " + reason), name_(what_name) {}
  /// The argument or key that was refused.
  const std::string& name() const noexcept { return name_; }

 private:
  std::string name_;
};

}  // namespace fremond
