#pragma once
// The scene's law restricted to the contacts of one impact. A law with per-contact parameters (e,
// μ or potentials given one per contact) is solved with the parameters of the contacts that take
// part, in their order; each subset is built once per run.
#include <cstdint>
#include <map>

#include "fremond/laws/impact_law.hpp"

namespace fremond::detail {

class ContactLaws {
 public:
  ContactLaws() = default;
  explicit ContactLaws(const ImpactLaw& law);
  /// The law of the contacts idx[0..n) (scene contact indices).
  const ImpactLaw& of(const int* idx, int n);

 private:
  using Mask = std::uint32_t;
  const ImpactLaw* law_ = nullptr;
  bool uniform_ = true;  ///< one value of every parameter for all contacts
  std::map<Mask, ImpactLaw> restricted_;
};

}  // namespace fremond::detail
