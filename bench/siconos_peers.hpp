#pragma once
/// @file Siconos peers of our solvers, for the benchmarks: Siconos Numerics' LCP and 2-D
/// friction-contact solvers on one impact, and Siconos Kernel's Moreau-Jean time stepping on the
/// bar of the paper's Fig. 1.
///
/// This header names no Siconos type and needs only C++17, so the benchmarks that include it build
/// in the project's C++20 while the peers themselves (siconos_peers.cpp: Siconos Kernel's headers
/// do not compile as C++20) build apart as C++17. It is only usable when CMake found Siconos
/// (FREMOND_HAVE_SICONOS); without it the benchmarks say so and skip.
///
/// Conventions (Siconos's, which match docs/concepts.md here): an LCP is `w = M z + q, 0 ≤ z ⊥ w ≥
/// 0`; a 2-D friction-contact problem is `u = M r + q` with, per contact, r = (r_N, r_T), u = (u_N,
/// u_T), 0 ≤ u_N ⊥ r_N ≥ 0 and Coulomb's law |r_T| ≤ μ r_N, r_T = −μ r_N sign(u_T) where u_T ≠ 0.
/// For a Newton + Coulomb impact, M = G (rows N, T contact by contact), r = P, q = ((1 + e) D_NA,
/// D_TA), so u_N = D_NE + e D_NA and u_T = D_TE (docs/laws.md). Matrices are column-major.
#include <memory>
#include <string>
#include <vector>

namespace fremond::bench::siconos {

/// Siconos Numerics' LCP solvers (SICONOS_LCP_*), run through linearComplementarity_driver.
enum class LcpSolver {
  lemke,        ///< SICONOS_LCP_LEMKE: lexicographic Lemke pivoting.
  enumeration,  ///< SICONOS_LCP_ENUM: every active set.
  pgs,          ///< SICONOS_LCP_PGS: projected Gauss-Seidel.
  newton_fb,    ///< SICONOS_LCP_NEWTON_FB_FBLSA: Newton on Fischer-Burmeister with line search.
};

/// Siconos Numerics' 2-D friction-contact solvers (SICONOS_FRICTION_2D_*), run through fc2d_driver.
enum class Fc2dSolver {
  nsgs,         ///< SICONOS_FRICTION_2D_NSGS: non-smooth Gauss-Seidel over the contacts.
  lemke,        ///< SICONOS_FRICTION_2D_LEMKE: the problem as an LCP, then Lemke.
  enumeration,  ///< SICONOS_FRICTION_2D_ENUM: the LCP form, every active set.
  cpg,          ///< SICONOS_FRICTION_2D_CPG: conjugate projected gradient.
};

const char* to_string(LcpSolver s);
const char* to_string(Fc2dSolver s);

/// How a Siconos solve ended: the driver's info (0 = solved), with the iterations and the residual
/// that Siconos wrote back into its options.
struct SolveInfo {
  int info = -1;
  int iterations = 0;
  double residual = 0.0;
};

/// One LCP of size n held in Siconos's structures, built once; solve() copies M and q in and calls
/// the driver, which is what a Siconos user does per impact.
class Lcp {
 public:
  Lcp(int n, LcpSolver solver, double tolerance = 1e-14, int max_iterations = 10000);
  ~Lcp();
  Lcp(const Lcp&) = delete;
  Lcp& operator=(const Lcp&) = delete;
  /// M: n×n column-major; q: n. Writes z and w (n each).
  SolveInfo solve(const double* M, const double* q, double* z, double* w);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One 2-D friction-contact problem with `contacts` contacts (size 2·contacts), built once.
class FrictionContact2d {
 public:
  FrictionContact2d(int contacts, Fc2dSolver solver, double tolerance = 1e-14,
                    int max_iterations = 10000);
  ~FrictionContact2d();
  FrictionContact2d(const FrictionContact2d&) = delete;
  FrictionContact2d& operator=(const FrictionContact2d&) = delete;
  /// M: 2c×2c column-major; q: 2c; mu: c. Writes r and u (2c each).
  SolveInfo solve(const double* M, const double* q, const double* mu, double* r, double* u);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A friction-contact file read by Siconos's own reader (frictionContact_new_from_filename) and
/// put in dense storage, which its 2-D drivers need; solve() runs fc2d_driver from r = 0.
class Fc2dFile {
 public:
  Fc2dFile(const std::string& path, Fc2dSolver solver, double tolerance, int max_iterations);
  ~Fc2dFile();
  Fc2dFile(const Fc2dFile&) = delete;
  Fc2dFile& operator=(const Fc2dFile&) = delete;
  int contacts() const;
  /// Writes r and u (2c each, rows (normal, tangent) per contact).
  SolveInfo solve(std::vector<double>& r, std::vector<double>& u);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Siconos Kernel's Moreau-Jean on the bar of the paper's Fig. 1: a LagrangianLinearTIDS q = (x, y,
/// θ) with M = diag(m, m, m l²/3) and weight −m g on y, one Interaction per end (a
/// LagrangianScleronomousR with h = y ± l sin θ and the Jacobian rows W_Nᵀ, W_Tᵀ of the paper's
/// Fig. 1) under NewtonImpactFrictionNSL, a FrictionContact(2) one-step problem,
/// MoreauJeanOSI(θ_MJ) and TimeStepping.
struct MoreauJeanSettings {
  double h = 1e-4;        ///< time step, s.
  double duration = 3.0;  ///< simulated time, s.
  double e = 0.9;         ///< Newton's restitution (normal).
  double mu = 1.0;        ///< Coulomb's coefficient.
  double theta = 0.5;     ///< Moreau-Jean's θ (0.5: the trapezoidal rule on smooth forces).
  Fc2dSolver solver = Fc2dSolver::nsgs;  ///< the one-step problem's solver.
  double tolerance = 1e-12;              ///< that solver's tolerance.
};

/// What one run gave. An impact is a step where an end's normal percussion becomes positive after a
/// step without one (the first step of each contact period).
struct MoreauJeanRun {
  int steps = 0;
  double seconds = 0.0;                ///< wall time of the stepping loop alone.
  double cpu_seconds = 0.0;            ///< CPU time of this thread in the stepping loop.
  double microseconds_per_step = 0.0;  ///< CPU µs per step.
  std::vector<double> impact_times;    ///< both ends, in time order.
  std::vector<int> impact_ends;        ///< which end (+1 or −1) for each impact time.
  double max_penetration = 0.0;        ///< max over steps and ends of max(0, −end height), m.
  std::vector<double> qdot_after_first_impact;  ///< q̇ at the end of the first impact's step.
  std::vector<double> q_final, qdot_final;
  double energy_initial = 0.0, energy_final = 0.0;  ///< ½ q̇ᵀMq̇ + m g y (the paper's Fig. 1).
  double energy_max_increase = 0.0;  ///< max over steps of E(t_{k+1}) − E(t_k), ≥ 0.
};

MoreauJeanRun simulate_bar_moreau_jean(const MoreauJeanSettings& settings = {});

/// The Siconos version the peers were built against, e.g. "4.4.0".
std::string version();

}  // namespace fremond::bench::siconos
