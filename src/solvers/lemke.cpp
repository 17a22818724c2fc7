// The public LCP solver: input checks around the lexicographic Lemke kernel of detail/lemke.hpp.
#include "fremond/solvers/lemke.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "fremond/core/enum_names.hpp"
#include "fremond/core/error.hpp"
#include "solvers/detail/lemke.hpp"

namespace fremond {

namespace {
constexpr detail::EnumNames<LcpStatus, 5> kLcpStatus{{{LcpStatus::not_run, "not_run"},
                                                      {LcpStatus::solved, "solved"},
                                                      {LcpStatus::secondary_ray, "secondary_ray"},
                                                      {LcpStatus::max_pivots, "max_pivots"},
                                                      {LcpStatus::failed, "failed"}}};
}  // namespace

std::string_view to_string(LcpStatus s) {
  return detail::enum_to_string(kLcpStatus, s);
}
LcpStatus lcp_status_from_string(std::string_view s) {
  return detail::enum_from_string(kLcpStatus, s, "lcp_status");
}

bool LemkeOptions::is_valid(std::string* why) const {
  auto no = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (max_pivots < 1) return no("max_pivots: must be >= 1");
  if (!(pivot_tolerance >= 1e-16 && pivot_tolerance <= 1e-3))
    return no("pivot_tolerance: must be in [1e-16, 1e-3]");
  if (!(tie_tolerance >= 1e-16 && tie_tolerance <= 1e-3))
    return no("tie_tolerance: must be in [1e-16, 1e-3]");
  return true;
}

void LemkeOptions::validate() const {
  std::string why;
  if (is_valid(&why)) return;
  const auto colon = why.find(':');
  throw InvalidArgument("LemkeOptions." + why.substr(0, colon), why.substr(colon + 2));
}

template <int Max>
double lcp_residual(const MatT<Max, Max>& M, const VecT<Max>& q, const VecT<Max>& z) {
  VecT<Max> w;
  const double err = detail::lcp::complementarity_error(M, q, z, w);
  const double scale = q.size() ? q.cwiseAbs().maxCoeff() : 0.0;
  return err / std::max(scale, std::numeric_limits<double>::min());
}

template <int Max>
LcpResultT<Max> solve_lcp(const MatT<Max, Max>& M, const VecT<Max>& q,
                          const LemkeOptions& options) {
  options.validate();
  if (M.rows() != M.cols() || M.rows() != q.size())
    throw InvalidArgument("M", "must be square of the size of q (" + std::to_string(q.size()) +
                                   "), got " + std::to_string(M.rows()) + "x" +
                                   std::to_string(M.cols()));
  if (!M.allFinite()) throw InvalidArgument("M", "every entry must be a finite number");
  if (!q.allFinite()) throw InvalidArgument("q", "every entry must be a finite number");
  LcpResultT<Max> out;
  out.status = detail::lcp::lemke<Max>(M, q, options, out.z, out.w, out.pivots);
  if (out.status == LcpStatus::solved) out.residual = lcp_residual<Max>(M, q, out.z);
  return out;
}

template LcpResultT<Dynamic> solve_lcp(const MatT<Dynamic, Dynamic>&, const VecT<Dynamic>&,
                                       const LemkeOptions&);
template LcpResultT<kSmallLcp> solve_lcp(const MatT<kSmallLcp, kSmallLcp>&, const VecT<kSmallLcp>&,
                                         const LemkeOptions&);
template double lcp_residual(const MatT<Dynamic, Dynamic>&, const VecT<Dynamic>&,
                             const VecT<Dynamic>&);
template double lcp_residual(const MatT<kSmallLcp, kSmallLcp>&, const VecT<kSmallLcp>&,
                             const VecT<kSmallLcp>&);

}  // namespace fremond
