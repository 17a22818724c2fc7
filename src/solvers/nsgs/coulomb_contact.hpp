#pragma once
/// @file One contact of Newton's law with Coulomb friction, solved exactly given the others'
/// percussions (the local problem of nonsmooth Gauss–Seidel, docs/sparse.md).
#include <algorithm>
#include <cmath>

namespace fremond::detail {

/// (P_N, P_T) of one contact.
struct ContactPercussion {
  double N = 0.0, T = 0.0;
};

/// The contact's block of G, [[a, b], [c, d]] (row normal, row tangent); c = b when G is
/// symmetric, kept apart for a G read from a file with a few digits.
struct ContactBlock {
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;
};

/// With w = f + A P (A the contact's block, f its velocity with every other percussion and the
/// restitution term e min(D_NA, 0) in the normal row): 0 ≤ P_N ⊥ w_N ≥ 0, |P_T| ≤ μ P_N, and
/// P_T = −μ P_N sign(w_T) where w_T ≠ 0. Modes in turn: apart (f_N ≥ 0), stick, slide either
/// way; exact wherever one holds. Where none does (μ|b| > a, Painlevé's case), a projected step
/// from `previous`, so that the sweeps still move toward a solution if one exists.
inline ContactPercussion coulomb_contact(const ContactBlock& A, double fN, double fT, double mu,
                                         ContactPercussion previous) {
  if (!(fN < 0.0)) return {};
  const double PN0 = -fN / A.a;
  const double wT0 = fT + A.c * PN0;
  if (mu == 0.0 || wT0 == 0.0) return {PN0, 0.0};
  const double det = A.a * A.d - A.b * A.c;
  if (det > 1e-14 * A.a * A.d) {
    const double PN = (-fN * A.d + fT * A.b) / det;
    const double PT = (-fT * A.a + fN * A.c) / det;
    if (PN >= 0.0 && std::fabs(PT) <= mu * PN) return {PN, PT};
  }
  // Slide against the slip of the normal-only answer first: the mode that holds unless μ|b| > a.
  const double first = wT0 > 0.0 ? 1.0 : -1.0;
  for (const double s : {first, -first}) {
    const double k = A.a - s * mu * A.b;
    if (!(k > 0.0)) continue;
    const double PN = -fN / k;
    if (s * (fT + (A.c - s * mu * A.d) * PN) >= 0.0) return {PN, -s * mu * PN};
  }
  const double PN = std::max(0.0, previous.N - (fN + A.a * previous.N + A.b * previous.T) / A.a);
  const double g = A.d > 0.0 ? A.d : A.a;
  const double PT =
      std::clamp(previous.T - (fT + A.c * PN + A.d * previous.T) / g, -mu * PN, mu * PN);
  return {PN, PT};
}

}  // namespace fremond::detail
