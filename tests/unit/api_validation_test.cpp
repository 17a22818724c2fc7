// The public C++ API refuses what is not valid (NaN, infinities, sizes, ranges) with an
// InvalidArgument whose name() is the argument, never a crash, a silent default or a NaN answer.
// Grouped by entry point: solve_impact (problem, law, options), solve_impact_all, the potentials'
// constructors and operations, the registry, the small form, law_residual and the certificate.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "fremond/fremond.hpp"
#include "fremond/io/problem_file.hpp"
#include "stress/invariants.hpp"

namespace fremond {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// The name of the InvalidArgument `f` throws; "<none>" when it returns, "<other: ...>" when it
// throws anything else.
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    EXPECT_GT(std::string(e.what()).size(), e.name().size() + 2) << "no reason given: " << e.what();
    return e.name();
  } catch (const std::exception& e) {
    return std::string("<other: ") + e.what() + ">";
  }
  return "<none>";
}

// A valid two-contact problem with tangential rows: every test breaks one thing in it.
ImpactProblem base_problem() {
  ImpactProblem pb;
  pb.M = Eigen::Matrix3d::Identity();
  pb.M(2, 2) = 1.0 / 12.0;
  pb.W_N.resize(3, 2);
  pb.W_N << 0, 0, 1, 1, -0.5, 0.5;
  pb.W_T.resize(3, 2);
  pb.W_T << 1, 1, 0, 0, 0, 0;
  pb.qdot_A = Eigen::Vector3d(1.0, -2.0, 0.5);
  return pb;
}

ImpactLaw fremond_law() {
  return ImpactLaw::fremond(PowerPotential(6.0, 2.0));
}

std::string solve_refusal(const ImpactProblem& pb, const ImpactLaw& law = ImpactLaw::newton(0.5),
                          const SolverOptions& opt = {}) {
  return refusal([&] { (void)solve_impact(pb, law, opt); });
}

// ---------------------------------------------------------------------------------------------
// solve_impact: the problem

TEST(ApiValidation, TheBaseProblemIsValid) {
  EXPECT_EQ(solve_refusal(base_problem()), "<none>");
  EXPECT_EQ(solve_refusal(base_problem(), fremond_law()), "<none>");
}

TEST(ApiValidation, MassMatrixNaNInfinityShapeSymmetryDefiniteness) {
  for (double bad : {kNaN, kInf, -kInf}) {
    ImpactProblem pb = base_problem();
    pb.M(1, 2) = pb.M(2, 1) = bad;
    const std::string name = solve_refusal(pb);
    EXPECT_TRUE(name == "M[1][2]" || name == "M[2][1]") << bad << ": " << name;
  }
  ImpactProblem pb = base_problem();
  pb.M.resize(0, 0);
  EXPECT_EQ(solve_refusal(pb), "M");
  pb = base_problem();
  pb.M.conservativeResize(3, 2);
  EXPECT_EQ(solve_refusal(pb), "M");
  pb = base_problem();
  pb.M(0, 1) = 0.5;  // not symmetric
  EXPECT_EQ(solve_refusal(pb), "M");
  pb = base_problem();
  pb.M(2, 2) = -1.0;  // not positive definite
  EXPECT_EQ(solve_refusal(pb), "M");
  pb = base_problem();
  pb.M(2, 2) = 0.0;  // singular
  EXPECT_EQ(solve_refusal(pb), "M");
  pb = base_problem();
  pb.M(2, 2) = 1e-40;  // positive, but rounding noise next to 1
  EXPECT_EQ(solve_refusal(pb), "M");
}

TEST(ApiValidation, ContactJacobiansSizesAndNumbers) {
  ImpactProblem pb = base_problem();
  pb.W_N(2, 1) = kNaN;
  EXPECT_EQ(solve_refusal(pb), "W_N[2][1]");
  pb = base_problem();
  pb.W_N(0, 0) = kInf;
  EXPECT_EQ(solve_refusal(pb), "W_N[0][0]");
  pb = base_problem();
  pb.W_N.conservativeResize(2, 2);  // rows ≠ dofs
  EXPECT_EQ(solve_refusal(pb), "W_N");
  pb = base_problem();
  pb.W_T(1, 0) = -kInf;
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 0.3)), "W_T[1][0]");
  pb = base_problem();
  pb.W_T.conservativeResize(3, 1);  // one column for two contacts
  EXPECT_EQ(solve_refusal(pb), "W_T");
  pb = base_problem();
  pb.W_T.conservativeResize(2, 2);
  EXPECT_EQ(solve_refusal(pb), "W_T");
}

TEST(ApiValidation, ObstacleVelocitiesAndVelocityBefore) {
  ImpactProblem pb = base_problem();
  pb.w_N = Eigen::Vector3d::Zero();  // three entries for two contacts
  EXPECT_EQ(solve_refusal(pb), "w_N");
  pb = base_problem();
  pb.w_N = Eigen::Vector2d(0.0, kNaN);
  EXPECT_EQ(solve_refusal(pb), "w_N[1]");
  pb = base_problem();
  pb.w_T = Eigen::Vector2d(kInf, 0.0);
  EXPECT_EQ(solve_refusal(pb), "w_T[0]");
  pb = base_problem();
  pb.w_T = Eigen::VectorXd::Zero(1);
  EXPECT_EQ(solve_refusal(pb), "w_T");
  pb = base_problem();
  pb.W_T.resize(3, 0);
  pb.w_T = Eigen::Vector2d::Zero();  // w_T without W_T
  EXPECT_EQ(solve_refusal(pb), "w_T");
  pb = base_problem();
  pb.qdot_A = Eigen::Vector2d(1.0, -1.0);
  EXPECT_EQ(solve_refusal(pb), "qdot_A");
  for (double bad : {kNaN, kInf, -kInf}) {
    pb = base_problem();
    pb.qdot_A(1) = bad;
    EXPECT_EQ(solve_refusal(pb), "qdot_A[1]") << bad;
  }
}

// Finite data whose energy or contact velocities overflow cannot be certified (T_E − T_A would be
// ∞ − ∞): refused by name, for every law and for the small form alike. Just inside the range the
// problem is solved, and nothing non-finite comes back.
TEST(ApiValidation, EnergyOrContactVelocityBeyondDoublePrecision) {
  ImpactProblem pb = base_problem();
  pb.qdot_A = Eigen::Vector3d(0.0, -3e154, 0.0);  // ½·(3e154)² = 4.5e308 > DBL_MAX
  EXPECT_EQ(solve_refusal(pb), "qdot_A");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::poisson_coulomb(0.5, 0.3)), "qdot_A");
  EXPECT_EQ(solve_refusal(pb, fremond_law()), "qdot_A");
  EXPECT_EQ(refusal([&] { (void)solve_impact(to_small(pb), ImpactLaw::newton(0.5)); }), "qdot_A");
  pb.qdot_A = Eigen::Vector3d(0.0, -1e150, 0.0);  // T_A = 5e299: representable
  EXPECT_EQ(solve_refusal(pb), "<none>");
  const auto r = solve_impact(pb, ImpactLaw::newton(0.5));
  EXPECT_TRUE(std::isfinite(r.energy_change));
  EXPECT_EQ(r.solver.status, SolverStatus::converged);
  // Newton, e = 0.5, both ends of a flat body with D_NA = -1e150: T_E − T_A = −(1 − e²) T_A.
  EXPECT_NEAR(r.energy_change / (-0.75 * 0.5e300), 1.0, 1e-12);

  // A small kinetic energy, but a contact velocity that overflows: D_NA(0) = 1e308·(−2).
  pb = base_problem();
  pb.W_N(1, 0) = 1e308;
  EXPECT_EQ(solve_refusal(pb), "W_N");
  pb.W_N(1, 0) = 1e307;  // D_NA(0) = −2e307 is in range, but G = 1e614 is not: refused for that
  try {
    (void)solve_impact(pb, ImpactLaw::newton(0.5));
    ADD_FAILURE() << "not refused";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "W_N");
    EXPECT_NE(std::string(e.what()).find("Delassus"), std::string::npos) << e.what();
  }
  // D_TA(0) = 1e308·1 + 1.7e308 (a moving obstacle).
  pb = base_problem();
  pb.W_T(0, 0) = 1e308;
  pb.w_T = Eigen::Vector2d(1.7e308, 0.0);
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 0.3)), "W_T");

  // Finite velocities, but a Delassus entry G = Wᵀ M⁻¹ W = (1e160)² that overflows, for a contact
  // that takes part (D_NA(0) = −2e160): refused by name before any factorisation sees ∞. The solver
  // fuzzer found Eigen's SVD reading out of bounds on such a G (Newton + Coulomb, 3 contacts).
  pb = base_problem();
  pb.W_N(1, 0) = 1e160;
  EXPECT_EQ(solve_refusal(pb), "W_N");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.2, PerContact({1e6, 0.0}))), "W_N");
  EXPECT_EQ(solve_refusal(pb, fremond_law()), "W_N");
  EXPECT_EQ(refusal([&] { (void)solve_impact_all(pb, ImpactLaw::newton_coulomb(0.2, 1e6)); }),
            "W_N");
  pb.W_N(1, 0) = 1e150;  // G = 1e300: in range, solved, and the answer is finite
  const auto big = solve_impact(pb, ImpactLaw::newton_coulomb(0.2, 0.5));
  EXPECT_TRUE(big.qdot_E.allFinite() && std::isfinite(big.energy_change));
  EXPECT_EQ(robust::check_result(pb, ImpactLaw::newton_coulomb(0.2, 0.5), {}, big), "");
  pb = base_problem();
  pb.W_T(0, 0) = 1e160;  // the tangential row of contact 0
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 0.3)), "W_T");
  EXPECT_EQ(solve_refusal(pb), "<none>");  // frictionless: the tangential rows take no part
  // A tangential entry so large that the coupling W_Nᵀ M⁻¹ W_T of the same contact overflows too
  // (−0.5 · 12 · 3.5e307): the tangential row, whose own entry overflows, is named, not the
  // normal row whose column holds the coupling (problem-file fuzzing).
  pb = base_problem();
  pb.W_T(2, 0) = 3.5e307;
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 0.3)), "W_T");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::fremond_coulomb(PowerPotential(2.0, 2.0), 5.0)), "W_T");
}

// A problem without contacts is legal (nothing happens); it must not crash either way.
TEST(ApiValidation, NoContactsIsTrivialOrRefused) {
  ImpactProblem pb = base_problem();
  pb.W_N.resize(3, 0);
  pb.W_T.resize(3, 0);
  for (const ImpactLaw& law : {ImpactLaw::newton(0.5), fremond_law()}) {
    try {
      const auto r = solve_impact(pb, law);
      EXPECT_TRUE(r.ok()) << r.solver.message;
      EXPECT_EQ(r.qdot_E, pb.qdot_A);
      EXPECT_EQ(robust::check_result(pb, law, SolverOptions{}, r), "");
    } catch (const InvalidArgument& e) {
      EXPECT_FALSE(e.name().empty());
    }
  }
}

// ---------------------------------------------------------------------------------------------
// solve_impact: the law

// A law's values are refused where it is made; its count against the problem where it is solved.
TEST(ApiValidation, RestitutionRangeAndNumbers) {
  const ImpactProblem pb = base_problem();
  for (double bad : {kNaN, kInf, -kInf, -1e-300, 1.0 + 1e-15, 2.0})
    EXPECT_EQ(refusal([&] { (void)ImpactLaw::newton(bad); }), "law.e") << bad;
  EXPECT_EQ(refusal([&] { (void)ImpactLaw::poisson(PerContact({0.5, kNaN})); }), "law.e[1]");
  EXPECT_EQ(refusal([&] { (void)ImpactLaw::newton(PerContact(std::vector<double>{})); }), "law.e");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton(PerContact({0.5, 0.5, 0.5}))), "law.e");
  // A law's values set on its value type are checked where it becomes an ImpactLaw.
  RestitutionLaw raw;
  raw.e = PerContact(-0.5);
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(raw); }), "law.e");
  // The edges are valid.
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton(0.0)), "<none>");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton(1.0)), "<none>");
}

TEST(ApiValidation, FrictionRangeAndNumbers) {
  const ImpactProblem pb = base_problem();
  for (double bad : {kNaN, kInf, -kInf, -1e-300}) {
    EXPECT_EQ(refusal([&] { (void)ImpactLaw::newton_coulomb(0.5, bad); }), "law.mu") << bad;
    EXPECT_EQ(refusal([&] { (void)ImpactLaw::fremond_coulomb(PowerPotential(6, 2), bad); }),
              "law.mu")
        << bad;
  }
  EXPECT_EQ(refusal([&] {
              (void)ImpactLaw::poisson_coulomb(0.5, PerContact({0.1, -1.0}));
            }),
            "law.mu[1]");
  // Lists of different lengths cannot fit one problem.
  EXPECT_EQ(refusal([&] {
              (void)ImpactLaw::newton_coulomb(PerContact({0.5, 0.5}), PerContact({0.1, 0.1, 0.1}));
            }),
            "law.e");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, PerContact({0.1, 0.1, 0.1}))),
            "law.mu");
  RestitutionLaw raw{RestitutionLaw::Kind::newton, 0.5, true, 0.1};
  raw.mu = PerContact(-1.0);
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(raw); }), "law.mu");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 0.0)), "<none>");
  EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton_coulomb(0.5, 1e300)), "<none>");
}

TEST(ApiValidation, FremondPotentialsPresentAndCounted) {
  const ImpactProblem pb = base_problem();
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(FremondLaw{}); }), "law.normal");  // no normal potential
  FremondLaw three = fremond_law().get<FremondLaw>();
  three.normal.potentials.emplace_back(PowerPotential(1, 2).clone());
  three.normal.potentials.emplace_back(PowerPotential(1, 2).clone());  // three for two contacts
  EXPECT_EQ(solve_refusal(pb, ImpactLaw(three)), "law.normal");
  FremondLaw null = fremond_law().get<FremondLaw>();
  null.normal.potentials.emplace_back(nullptr);
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(null); }), "law.normal");
  FremondLaw no_potential = fremond_law().get<FremondLaw>();
  no_potential.tangential = TangentialLaw::potential;  // without a tangential potential
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(no_potential); }), "law.tangential");
  FremondLaw null_tangential =
      ImpactLaw::fremond(PowerPotential(6, 2), DeadZonePowerPotential(1, 2, 0)).get<FremondLaw>();
  null_tangential.tangential_potential.potentials.emplace_back(nullptr);
  EXPECT_EQ(refusal([&] { (void)ImpactLaw(null_tangential); }), "law.tangential");
  // Asking a law for another law's values names both.
  EXPECT_EQ(refusal([&] { (void)ImpactLaw::newton(0.5).get<FremondLaw>(); }), "law");
}

// ---------------------------------------------------------------------------------------------
// solve_impact: the options

TEST(ApiValidation, SolverOptionsRanges) {
  const ImpactProblem pb = base_problem();
  auto with = [](auto set) {
    SolverOptions o;
    set(o);
    return o;
  };
  for (double bad : {kNaN, kInf, 0.0, -1e-13, 1e-17, 0.1})
    EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton(0.5),
                            with([&](SolverOptions& o) { o.tolerance = bad; })),
              "tolerance")
        << bad;
  for (double bad : {kNaN, kInf, 0.0, 1e-17, 0.5})
    EXPECT_EQ(solve_refusal(pb, ImpactLaw::newton(0.5),
                            with([&](SolverOptions& o) { o.nlopt_tolerance = bad; })),
              "nlopt_tolerance")
        << bad;
  EXPECT_EQ(solve_refusal(pb, fremond_law(), with([](SolverOptions& o) { o.max_iterations = 0; })),
            "max_iterations");
  EXPECT_EQ(solve_refusal(pb, fremond_law(),
                          with([](SolverOptions& o) { o.max_proximal_iterations = -1; })),
            "max_proximal_iterations");
  EXPECT_EQ(
      solve_refusal(pb, fremond_law(), with([](SolverOptions& o) { o.max_nlopt_evaluations = 0; })),
      "max_nlopt_evaluations");
  for (double bad : {kNaN, kInf, -1e-9, 1.0})
    EXPECT_EQ(solve_refusal(pb, fremond_law(),
                            with([&](SolverOptions& o) { o.admissibility_tolerance = bad; })),
              "admissibility_tolerance")
        << bad;
  std::string why;
  EXPECT_FALSE(with([](SolverOptions& o) { o.tolerance = kNaN; }).is_valid(&why));
  EXPECT_NE(why.find("tolerance"), std::string::npos);
  EXPECT_TRUE(SolverOptions{}.is_valid());
}

// solve_impact_all checks exactly what solve_impact checks.
TEST(ApiValidation, SolveImpactAllValidatesToo) {
  ImpactProblem pb = base_problem();
  pb.qdot_A(0) = kNaN;
  EXPECT_EQ(refusal([&] { (void)solve_impact_all(pb, ImpactLaw::newton_coulomb(0.5, 1.0)); }),
            "qdot_A[0]");
  EXPECT_EQ(refusal([&] {
              (void)solve_impact_all(base_problem(), ImpactLaw::newton_coulomb(kNaN, 1.0));
            }),
            "law.e");
  SolverOptions o;
  o.tolerance = -1;
  EXPECT_EQ(refusal([&] { (void)solve_impact_all(base_problem(), fremond_law(), o); }),
            "tolerance");
}

// The stack-stored form validates the same way, and refuses what does not fit it.
TEST(ApiValidation, SmallFormValidatesAndRefusesWhatDoesNotFit) {
  ImpactProblem pb = base_problem();
  SmallImpactProblem small = to_small(pb);
  small.qdot_A(2) = kInf;
  EXPECT_EQ(refusal([&] { (void)solve_impact(small, ImpactLaw::newton(0.5)); }), "qdot_A[2]");
  ImpactProblem big;
  big.M = Eigen::MatrixXd::Identity(kSmallDofs + 1, kSmallDofs + 1);
  big.W_N = Eigen::MatrixXd::Ones(kSmallDofs + 1, 1);
  big.W_T.resize(kSmallDofs + 1, 0);
  big.qdot_A = -Eigen::VectorXd::Ones(kSmallDofs + 1);
  EXPECT_FALSE(fits_small(big));
  EXPECT_EQ(refusal([&] { (void)to_small(big); }), "problem");
}

// ---------------------------------------------------------------------------------------------
// Potentials

TEST(ApiValidation, PotentialConstructorsRefuseBadParameters) {
  for (double bad : {kNaN, kInf, -1.0}) {
    EXPECT_EQ(refusal([&] { PowerPotential(bad, 2.0); }), "k") << bad;
    EXPECT_EQ(refusal([&] { DeadZonePowerPotential(bad, 2.0, 0.1); }), "k") << bad;
    EXPECT_EQ(refusal([&] { DeadZonePowerPotential(1.0, 2.0, bad); }), "r") << bad;
    EXPECT_EQ(refusal([&] { AbsoluteValuePotential{bad}; }), "b") << bad;
  }
  for (double bad : {kNaN, kInf, 1.0, 0.5, -2.0}) {
    EXPECT_EQ(refusal([&] { PowerPotential(1.0, bad); }), "p") << bad;
    EXPECT_EQ(refusal([&] { DeadZonePowerPotential(1.0, bad, 0.0); }), "q") << bad;
  }
  EXPECT_EQ(refusal([] { PowerPotential(0.0, 1.0 + 1e-12); }), "<none>");  // edges are valid
  EXPECT_EQ(refusal([] { DeadZonePowerPotential(0.0, 1e6, 0.0); }), "<none>");
}

TEST(ApiValidation, ScaledAndSumPotentials) {
  const PowerPotential f(1.0, 2.0);
  for (double bad : {kNaN, kInf, 0.0, -1.0})
    EXPECT_NE(refusal([&] { ScaledPotential(bad, f); }), "<none>") << "alpha = " << bad;
  for (double bad : {kNaN, kInf, 0.0, -1.0}) {
    const std::string name = refusal([&] { (void)(bad * f); });
    EXPECT_NE(name, "<none>") << "alpha = " << bad;
    EXPECT_EQ(name.find("<other"), std::string::npos) << name;
  }
  EXPECT_EQ(refusal([&] { SumPotential(PotentialPtr{}, f.clone()); }).find("<other"),
            std::string::npos);
  EXPECT_NE(refusal([&] { SumPotential(PotentialPtr{}, f.clone()); }), "<none>");
}

TEST(ApiValidation, CallablePotentialNeedsValueAndSubgradient) {
  CallablePotentialParts parts;
  parts.value = [](double z) { return z * z; };
  EXPECT_NE(refusal([&] { CallablePotential{parts}; }), "<none>");
  parts.value = nullptr;
  parts.subgradient = [](double z) { return 2 * z; };
  EXPECT_NE(refusal([&] { CallablePotential{parts}; }), "<none>");
}

TEST(ApiValidation, ProxRefusesBadStepAndArgument) {
  const PowerPotential f(2.0, 3.0);
  for (double bad : {kNaN, kInf, 0.0, -1.0})
    EXPECT_EQ(refusal([&] { (void)f.prox(1.0, bad); }), "tau") << bad;
  EXPECT_EQ(refusal([&] { (void)f.prox(kNaN, 1.0); }), "x");
  // A potential with neither prox nor subdifferential has no prox to give.
  CallablePotentialParts parts;
  parts.value = [](double z) { return z * z; };
  parts.subgradient = [](double z) { return 2 * z; };
  const CallablePotential user(parts);
  EXPECT_NE(refusal([&] { (void)user.prox(1.0, 1.0); }), "<none>");
  EXPECT_NE(refusal([&] { (void)user.conjugate(1.0); }), "<none>");
  EXPECT_TRUE(std::isnan(user.fenchel_young_gap(1.0, 2.0)));  // documented: unknown conjugate
}

// ---------------------------------------------------------------------------------------------
// The registry

TEST(ApiValidation, RegistryRefusesBadNamesKindsAndParameters) {
  PotentialRegistry r = PotentialRegistry::with_builtins();
  EXPECT_EQ(refusal([&] {
              r.add("", {{}, {}, [](const PotentialParameters&) { return PotentialPtr{}; }, ""});
            }),
            "name");
  EXPECT_EQ(
      refusal([&] {
        r.add("power", {{}, {}, [](const PotentialParameters&) { return PotentialPtr{}; }, ""});
      }),
      "power");
  EXPECT_EQ(
      refusal([&] {
        r.add("coulomb", {{}, {}, [](const PotentialParameters&) { return PotentialPtr{}; }, ""});
      }),
      "coulomb");
  EXPECT_EQ(refusal([&] { r.add("mine", {{}, {}, nullptr, ""}); }), "mine.make");
  EXPECT_EQ(refusal([&] { (void)r.make("nope", {}); }), "potential");
  EXPECT_EQ(refusal([&] { (void)r.make("power", {{"k", 1.0}}, "law.normal"); }), "law.normal.p");
  EXPECT_EQ(refusal([&] {
              (void)r.make("power", {{"k", 1.0}, {"p", 2.0}, {"z", 1.0}}, "law.normal");
            }),
            "law.normal.z");
  EXPECT_EQ(refusal([&] {
              (void)r.make("power", {{"k", kNaN}, {"p", 2.0}}, "law.normal");
            }),
            "law.normal.k");
  EXPECT_EQ(refusal([&] {
              (void)r.make("deadzone_power", {{"k", 1.0}, {"q", 2.0}, {"r", -kInf}}, "t");
            }),
            "t.r");
  // A user's kind whose factory returns nothing: a file using it is refused, not dereferenced.
  r.add("empty", {{}, {}, [](const PotentialParameters&) { return PotentialPtr{}; }, ""});
  const std::string name = refusal([&] {
    (void)io::parse_problem_file(R"({"M": [[1]], "W_N": [[1]], "qdot_A": [-1],
                                    "law": {"type": "fremond", "normal": {"potential": "empty"}}})",
                                 r);
  });
  EXPECT_EQ(name.rfind("law.normal", 0), 0u) << name;
}

// ---------------------------------------------------------------------------------------------
// The certificate and the residual, given a result of the wrong shape (e.g. a default one)

TEST(ApiValidation, CertificateOfAnEmptyResultIsNotAdmissible) {
  const ImpactProblem pb = base_problem();
  for (const ImpactLaw& law :
       {ImpactLaw::newton(0.5), ImpactLaw::poisson_coulomb(0.5, 0.3), fremond_law()}) {
    const auto rep = check_admissibility(pb, law, ImpactResult{});
    EXPECT_FALSE(rep.admissible) << law.describe();
  }
}

// law_residual of a result of the wrong shape: the classical laws say infinity; Frémond's law
// is tests/unit/regression_fremond_test.cpp (it reads past the end of the result's vectors).
TEST(ApiValidation, ClassicalResidualOfAnEmptyResultIsRefused) {
  const ImpactProblem pb = base_problem();
  for (const ImpactLaw& law : {ImpactLaw::newton(0.5), ImpactLaw::poisson_coulomb(0.5, 0.3)}) {
    EXPECT_EQ(refusal([&] { (void)law_residual(pb, law, ImpactResult{}); }), "result")
        << law.describe();
    // A result of this problem is still accepted.
    EXPECT_TRUE(std::isfinite(law_residual(pb, law, solve_impact(pb, law)))) << law.describe();
  }
}

// ---------------------------------------------------------------------------------------------
// The problem file at the edges of the numbers JSON can hold.

TEST(ApiValidation, ProblemFileRefusesNumbersADoubleCannotHold) {
  const auto reg = PotentialRegistry::with_builtins();
  auto name = [&](const std::string& qdot) {
    return refusal([&] {
      (void)io::parse_problem_file(R"({"M": [[1]], "W_N": [[1]], "qdot_A": [)" + qdot +
                                       R"(], "law": {"type": "newton", "e": 0.5}})",
                                   reg);
    });
  };
  EXPECT_EQ(name("1e309"), "qdot_A[0]");
  EXPECT_EQ(name("-1e99999"), "qdot_A[0]");
  EXPECT_EQ(name("NaN"), "qdot_A[0]");
  EXPECT_EQ(name("Infinity"), "qdot_A[0]");
  EXPECT_EQ(name("-1e-400"), "<none>");  // underflows to −0: a number, and a legal one
}

}  // namespace
}  // namespace fremond

namespace fremond {
namespace {

// Every stopping criterion has a name the CLI and the bindings print and read back; an unknown
// name is refused naming the accepted ones.
TEST(ApiValidation, StopCriterionNamesRoundTrip) {
  for (StopCriterion c : {StopCriterion::none, StopCriterion::exact, StopCriterion::residual,
                          StopCriterion::step, StopCriterion::iterations, StopCriterion::nlopt,
                          StopCriterion::rounding, StopCriterion::data})
    EXPECT_EQ(stop_criterion_from_string(to_string(c)), c) << to_string(c);
  EXPECT_EQ(to_string(StopCriterion::rounding), "rounding");
  EXPECT_THROW((void)stop_criterion_from_string("roundoff"), InvalidArgument);
}

}  // namespace
}  // namespace fremond

namespace fremond {
namespace {

// A key holding a control character (JSON allows "\u0000"): the refusal names it with the
// character escaped, and its reason survives (a NUL used to cut what() to the bare name). Found by
// the problem-file fuzzer.
TEST(ApiValidation, KeyWithAControlCharacterIsNamedPrintably) {
  const auto reg = PotentialRegistry::with_builtins();
  try {
    (void)io::parse_problem_file("{\n  \"M\\u0000\"3", reg);
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    const std::string what = e.what();
    EXPECT_GT(what.size(), e.name().size() + 2) << what;
    EXPECT_EQ(what.find('\0'), std::string::npos);
  }
  try {
    (void)io::parse_problem_file(
        R"({"M": [[1]], "W_N": [[1]], "qdot_A": [-1], "law": {"type": "newton", "e": 0.5}, "x\u0001y": 1})",
        reg);
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "x\\u0001y");
    EXPECT_NE(std::string(e.what()).find("unknown key"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fremond
