#pragma once
/// @file A general linear complementarity solver: find z with
///
///     w = M z + q,   w ≥ 0,   z ≥ 0,   wᵀz = 0,
///
/// by Lemke's complementary pivoting with the lexicographic ratio test (Cottle, Pang & Stone, "The
/// Linear Complementarity Problem", §4.4). The lexicographic rule makes every pivot choice unique,
/// so the method cannot cycle on degenerate problems (several zero basic variables), which is the
/// usual case for impacts: a singular Delassus matrix, a contact that is exactly grazing.
///
/// What the answer means depends on M:
///  - M copositive-plus (e.g. symmetric positive semidefinite, the frictionless impact laws):
///    `secondary_ray` proves that the LCP has no solution (CPS Theorem 4.4.9);
///  - other M (e.g. the LCP form of Coulomb friction): `secondary_ray` only says Lemke's method
///    could not find a solution; one may still exist.
#include <limits>
#include <string>
#include <string_view>

#include "fremond/core/types.hpp"

namespace fremond {

/// How a Lemke solve ended.
enum class LcpStatus {
  not_run,        ///< the default: nothing was solved.
  solved,         ///< z ≥ 0, w = Mz + q ≥ 0, zᵀw = 0 (to rounding; see LcpResultT::residual).
  secondary_ray,  ///< no pivot row for the entering column: no solution was found (see file doc).
  max_pivots,     ///< LemkeOptions::max_pivots pivots done without reaching a solution.
  failed,         ///< non-finite numbers appeared; the answer is not usable.
};
std::string_view to_string(LcpStatus s);
/// Throws InvalidArgument naming the text and the accepted values.
LcpStatus lcp_status_from_string(std::string_view s);

/// Options of the Lemke solver. The solver never writes into them.
struct LemkeOptions {
  /// Pivot budget. Lexicographic Lemke ends in finitely many pivots (at most the number of bases,
  /// in practice a few times the size); this bounds the work on pathological input. Range ≥ 1.
  int max_pivots = 1000;
  /// An entry d_i of the entering column is a pivot candidate when d_i > pivot_tolerance · s, with
  /// s the larger of ‖d‖∞ and the largest entry of the column in the original data. Units: none.
  /// Range [1e-16, 1e-3].
  double pivot_tolerance = 1e-12;
  /// Two ratios of the lexicographic test are taken as tied when they differ by less than
  /// tie_tolerance times their size (plus a rounding floor); the next component then decides.
  /// Units: none. Range [1e-16, 1e-3].
  double tie_tolerance = 1e-11;
  /// After the last pivot, re-solve the final basis from the original M and q when the tableau's
  /// answer has a complementarity error above rounding (accumulated pivoting error). Costs one LU
  /// factorisation of the basis, only when needed.
  bool refine = true;

  /// True when every option is within its range; otherwise false with the reason in *why.
  bool is_valid(std::string* why = nullptr) const;
  /// Throws InvalidArgument naming the option when !is_valid().
  void validate() const;
};

/// The answer of a Lemke solve. MaxSize bounds the problem size; a finite bound keeps the result
/// (and the solve) on the stack.
template <int MaxSize>
struct LcpResultT {
  VecT<MaxSize> z;  ///< the solution (meaningful when status == solved).
  VecT<MaxSize> w;  ///< M z + q, recomputed from the original data.
  LcpStatus status = LcpStatus::not_run;
  int pivots = 0;  ///< complementary pivots done (0 when q ≥ 0: z = 0 is the answer).
  /// ‖min(z, w)‖∞ / max(‖q‖∞, tiny): zero exactly at a solution. NaN when not solved.
  double residual = std::numeric_limits<double>::quiet_NaN();

  bool ok() const { return status == LcpStatus::solved; }
};
using LcpResult = LcpResultT<Dynamic>;

/// Solves the LCP (M, q) by lexicographic Lemke. Throws InvalidArgument when M is not square of the
/// size of q, when an entry is not finite, or when the options are invalid. With a finite MaxSize
/// nothing is allocated on the heap.
template <int MaxSize>
LcpResultT<MaxSize> solve_lcp(const MatT<MaxSize, MaxSize>& M, const VecT<MaxSize>& q,
                              const LemkeOptions& options = {});

/// The scaled natural-map residual ‖min(z, Mz + q)‖∞ / max(‖q‖∞, tiny) of a candidate z (a negative
/// z_i or w_i shows in the min). Zero exactly at a solution.
template <int MaxSize>
double lcp_residual(const MatT<MaxSize, MaxSize>& M, const VecT<MaxSize>& q,
                    const VecT<MaxSize>& z);

/// The stack size of the instantiated small solver: 16 unknowns (4 planar contacts with friction).
inline constexpr int kSmallLcp = 16;
using SmallLcpResult = LcpResultT<kSmallLcp>;

}  // namespace fremond
