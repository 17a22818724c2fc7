// Fuzz target: the solvers, fed a small problem and a law decoded from the bytes (no JSON in the
// way, so the fuzzer spends its time in the solvers).
//
// Decoding (FuzzedDataProvider): sizes n ≤ 6, c ≤ 4; M = L Lᵀ with diagonal scales over 12 decades;
// contact directions with exact degeneracies on request (a zero column, a repeated column, W_T
// equal to W_N, a direction along a coordinate); velocities from 1e-12 to 1e8; every law with its
// parameters over their valid ranges and the edge values (e = 0, 1; μ = 0, huge; p, q near 1);
// built-in and composite potentials, and a user potential with value and subgradient only (the
// NLopt path); a method, forced or automatic. One input in eight takes raw doubles instead (NaN,
// infinities, denormals, negative masses): those must be refused with InvalidArgument, never
// crash.
//
// Checked: nothing but InvalidArgument escapes; every result satisfies tests/stress/invariants.hpp
// (a status; no NaN; converged ⇒ law_residual within tolerance; Frémond ⇒ admissible), for the
// heap-stored and the stack-stored forms, and for solve_impact_all.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "stress/problem_json.hpp"

using namespace fremond;

namespace {

class Decoder {
 public:
  Decoder(const std::uint8_t* data, std::size_t size) : fdp_(data, size) {}

  bool raw = false;

  int integer(int lo, int hi) { return fdp_.ConsumeIntegralInRange(lo, hi); }
  bool flag() { return fdp_.ConsumeBool(); }
  /// A number in [lo, hi], or any double in raw mode.
  double in(double lo, double hi) {
    if (raw && integer(0, 3) == 0) return fdp_.ConsumeFloatingPoint<double>();
    return fdp_.ConsumeFloatingPointInRange(lo, hi);
  }
  /// 10^u with u in [lo, hi].
  double decades(double lo, double hi) { return std::pow(10.0, in(lo, hi)); }

  double restitution() {
    switch (integer(0, 3)) {
      case 0:
        return 0.0;
      case 1:
        return 1.0;
      default:
        return in(0.0, 1.0);
    }
  }
  double friction() {
    switch (integer(0, 5)) {
      case 0:
        return 0.0;
      case 1:
        return 1e6;  // μ → ∞
      case 2:
        return 1e15;
      default:
        return decades(-3.0, 3.0);
    }
  }
  double exponent() {  // p, q > 1
    switch (integer(0, 4)) {
      case 0:
        return 2.0;
      case 1:
        return 1.0 + 1e-6;
      case 2:
        return 1.0 + in(1e-3, 0.1);
      default:
        return 1.0 + in(1e-2, 9.0);
    }
  }
  double stiffness() { return integer(0, 9) == 0 ? 0.0 : decades(-6.0, 6.0); }

  PerContact per_contact(int c, double (Decoder::*draw)()) {
    if (flag()) return PerContact((this->*draw)());
    std::vector<double> v(c);
    for (double& x : v) x = (this->*draw)();
    return PerContact(std::move(v));
  }

  PotentialPtr normal_potential() {
    switch (integer(0, 5)) {
      case 0: {
        const PowerPotential a(stiffness(), exponent()), b(stiffness(), exponent());
        return a + b;
      }
      case 1:
        return decades(-3.0, 3.0) * PowerPotential(stiffness(), exponent());
      default:
        return std::make_unique<PowerPotential>(stiffness(), exponent());
    }
  }
  PotentialPtr tangential_potential() {
    switch (integer(0, 5)) {
      case 0:
        return std::make_unique<AbsoluteValuePotential>(decades(-3.0, 3.0));
      case 1: {  // a user's potential with value and subgradient only: the NLopt fallback
        const double k = decades(-3.0, 3.0);
        CallablePotentialParts parts;
        parts.name = "user_quadratic";
        parts.value = [k](double y) { return 0.5 * k * y * y; };
        parts.subgradient = [k](double y) { return k * y; };
        return std::make_unique<CallablePotential>(std::move(parts));
      }
      default:
        return std::make_unique<DeadZonePowerPotential>(
            stiffness(), exponent(), integer(0, 2) == 0 ? 0.0 : decades(-6.0, 2.0));
    }
  }
  PerContactPotential potentials(int c, PotentialPtr (Decoder::*make)()) {
    PerContactPotential out;
    const int count = flag() ? 1 : c;
    for (int i = 0; i < count; ++i) out.potentials.emplace_back((this->*make)());
    return out;
  }

  ImpactLaw law(int c) {
    switch (integer(0, 6)) {
      case 0:
        return ImpactLaw::newton(per_contact(c, &Decoder::restitution));
      case 1:
        return ImpactLaw::poisson(per_contact(c, &Decoder::restitution));
      case 2:
        return ImpactLaw::newton_coulomb(per_contact(c, &Decoder::restitution),
                                         per_contact(c, &Decoder::friction));
      case 3:
        return ImpactLaw::poisson_coulomb(per_contact(c, &Decoder::restitution),
                                          per_contact(c, &Decoder::friction));
      case 4:
        return ImpactLaw::fremond(potentials(c, &Decoder::normal_potential));
      case 5:
        return ImpactLaw::fremond(potentials(c, &Decoder::normal_potential),
                                  potentials(c, &Decoder::tangential_potential));
      default:
        return ImpactLaw::fremond_coulomb(potentials(c, &Decoder::normal_potential),
                                          per_contact(c, &Decoder::friction));
    }
  }

  SmallImpactProblem problem() {
    const int n = integer(1, kSmallDofs), c = integer(1, kSmallContacts);
    const bool tangential = flag();
    SmallImpactProblem pb;
    // M = L Lᵀ, L lower triangular with diagonal scales over 12 decades.
    Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      L(i, i) = decades(-3.0, 3.0);
      for (int j = 0; j < i; ++j) L(i, j) = flag() ? 0.0 : in(-1.0, 1.0) * L(i, i);
    }
    Eigen::MatrixXd M = L * L.transpose();
    M = (0.5 * (M + M.transpose())).eval();
    if (raw && flag()) M(integer(0, n - 1), integer(0, n - 1)) = in(-1e300, 1e300);
    pb.M = M;
    auto direction = [&](Eigen::MatrixXd& W, int j, const Eigen::MatrixXd* other) {
      switch (integer(0, 7)) {
        case 0:
          W.col(j).setZero();
          break;  // a contact that cannot move
        case 1:
          if (j > 0) {
            W.col(j) = W.col(j - 1);
            break;
          }
          [[fallthrough]];  // a repeated row
        case 2:
          if (other) {
            W.col(j) = other->col(j);
            break;
          }
          [[fallthrough]];  // W_T = W_N
        case 3:
          W.col(j).setZero();
          W(integer(0, n - 1), j) = in(-2.0, 2.0);
          break;
        default:
          for (int i = 0; i < n; ++i) W(i, j) = in(-1.0, 1.0);
      }
    };
    Eigen::MatrixXd WN(n, c), WT(n, tangential ? c : 0);
    for (int j = 0; j < c; ++j) direction(WN, j, nullptr);
    for (int j = 0; j < WT.cols(); ++j) direction(WT, j, &WN);
    pb.W_N = WN;
    pb.W_T = WT;
    const double v = decades(-12.0, 8.0);
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = v * in(-1.0, 1.0);
    // Make the first contact approach (half the time), so that most inputs have an impact.
    const double dn = WN.col(0).dot(q);
    if (flag() && dn > 0.0 && WN.col(0).squaredNorm() > 0.0)
      q -= (2.0 * dn / WN.col(0).squaredNorm()) * Eigen::VectorXd(WN.col(0));
    pb.qdot_A = q;
    if (integer(0, 4) == 0) {  // moving obstacles
      pb.w_N.resize(c);
      for (int j = 0; j < c; ++j) pb.w_N(j) = v * in(-1.0, 1.0);
      if (tangential) {
        pb.w_T.resize(c);
        for (int j = 0; j < c; ++j) pb.w_T(j) = v * in(-1.0, 1.0);
      }
    }
    return pb;
  }

  SolverOptions options() {
    SolverOptions o;
    if (flag()) {
      static constexpr SolverMethod methods[] = {
          SolverMethod::trivial,       SolverMethod::closed_form,
          SolverMethod::scalar_newton, SolverMethod::mode_enumeration,
          SolverMethod::lemke,         SolverMethod::semismooth_newton,
          SolverMethod::proximal,      SolverMethod::nlopt};
      o.method = methods[integer(0, 7)];
    }
    o.check_uniqueness = flag();
    if (integer(0, 7) == 0) o.tolerance = decades(-16.0, -2.0);
    if (o.nlopt_tolerance < o.tolerance) o.nlopt_tolerance = o.tolerance;
    return o;
  }

 private:
  FuzzedDataProvider fdp_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Decoder d(data, size);
  d.raw = d.integer(0, 7) == 0;
  SmallImpactProblem pb;
  ImpactLaw law;
  SolverOptions options;
  try {
    pb = d.problem();
    law = d.law(pb.contacts());
    options = d.options();
  } catch (const InvalidArgument& e) {  // a potential refusing a raw parameter
    fuzz::check_refusal(e);
    return 0;
  }
  if (fuzz::classify_only(law)) return 0;
  // FREMOND_FUZZ_VERBOSE=1: print the decoded problem (as an impact-problem file) before solving,
  // to turn a crash or timeout input into a reproducer.
  static const bool verbose = [] {
    const char* v = std::getenv("FREMOND_FUZZ_VERBOSE");
    return v && *v && *v != '0';
  }();
  if (verbose)
    std::fprintf(stderr, "decoded (method %s, tolerance %g):\n%s\n",
                 std::string(to_string(options.method)).c_str(), options.tolerance,
                 robust::problem_to_json(pb, law).c_str());
  SmallImpactResult small;
  try {
    small = solve_impact(pb, law, options);
  } catch (const InvalidArgument& e) {
    fuzz::check_refusal(e);
    return 0;
  }
  fuzz::check(pb, law, options, small, "solve_impact (small)");
  const ImpactProblem dyn = to_dynamic(pb);
  const auto r = solve_impact(dyn, law, options);
  fuzz::check(dyn, law, options, r, "solve_impact");
  if (pb.contacts() <= 3 && options.method == SolverMethod::automatic) {
    const auto all = solve_impact_all(dyn, law, options);
    for (const auto& s : all) fuzz::check(dyn, law, options, s, "solve_impact_all");
  }
  return 0;
}
