#pragma once
/// @file Siconos's 2-D friction-contact problem files (docs/sparse.md), as its numerics library
/// writes and reads them: the local form (u = W r + q: the Delassus matrix, q, μ) and the global
/// form (M v = q + H r, u = Hᵀ v + b: M, H, q, b, μ). Either is Newton's law with e = 0 and
/// Coulomb friction, rows (normal, tangential) per contact.
#include <string_view>
#include <vector>

#include "fremond/laws/impact_law.hpp"
#include "fremond/sparse/contact_problem.hpp"

namespace fremond::io {

/// What a Siconos friction-contact file holds, in the library's terms.
struct SiconosProblem {
  enum class Form {
    local,   ///< contact: G = W (the file's Delassus matrix), D_A = q.
    global,  ///< impact: M, W = H (columns per contact), w = b, q̇_A = M⁻¹ q.
  };
  Form form = Form::local;
  /// The local form, validated. Its G_rounding and D_A_rounding follow the digits the file prints
  /// G's and q's numbers with: p, the most significant digits of any of them, gives 5·10⁻ᵖ
  /// (Siconos's own files print G sparse with 6, q with 25); numbers of fewer than 6 digits are
  /// taken as written by hand, exact (0).
  ContactProblem contact;
  SparseImpactProblem impact;  ///< the global form, validated.
  std::vector<double> mu;      ///< Coulomb's coefficient of each contact.

  int contacts() const { return static_cast<int>(mu.size()); }
  /// Newton + Coulomb, e = 0, the file's μ per contact: the law the file's problem poses.
  ImpactLaw law() const;
};

/// True when `text` begins as a Siconos file does (a line holding the dimension 2 or 3), so that a
/// command can tell it from a JSON problem file.
bool looks_like_siconos_file(std::string_view text);

/// Reads a Siconos 2-D friction-contact file, local (`fc2d_*.dat`) or global (`gfc2d_*.dat`); the
/// form is told by the file's layout. Matrices may be stored dense (type 0, column-major) or
/// sparse (type 2, as CSparse prints them: compressed columns or triplets). Throws
/// InvalidArgument named `line N` with the reason (a dimension other than 2, a count or size that
/// does not match, a number that does not parse or is not finite, an index out of range,
/// a storage type not read), or naming the member (`M`, `G`, `mu[3]`) the validation refuses.
SiconosProblem parse_siconos_file(std::string_view text);

}  // namespace fremond::io
