#pragma once
/// @file The law atlas (docs/atlas.md): one contact of a planar body swept over its impact
/// configurations, under several laws and a list of μ or e, to map where each law creates energy.
///
/// A configuration is the body's angle θ, the direction ψ of the contact point's velocity before
/// the impact, (D_TA, D_NA) = V (cos ψ, sin ψ) with ψ in [−π, 0] (the point approaches), and the
/// spin ratio s = θ̇ r_g / V, r_g = √(J/m) the radius of gyration. Its velocity before the impact is
/// the one q̇_A = (v, θ̇) with those contact velocities: n·v = D_NA − θ̇ W_N,θ, t·v = D_TA − θ̇
/// W_T,θ. Each point is one solve_impact of that one-contact problem (solved by solve_batch), with
/// its admissibility certificate.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/scenes/scene.hpp"
#include "fremond/solvers/solver_options.hpp"

namespace fremond {

/// The parameter an atlas sweeps, the other fixed.
enum class AtlasParameter : std::uint8_t {
  mu,  ///< Coulomb's μ (laws without friction ignore it).
  e,   ///< the restitution e (Frémond's: the normal stiffness calibrated to it, AtlasOptions).
};
std::string_view to_string(AtlasParameter p);
/// Throws InvalidArgument("parameter", ...) naming the accepted values.
AtlasParameter atlas_parameter_from_string(std::string_view s);

/// The contact's mode after the impact, the same reading for every law so that maps compare: from
/// |P_T| against Coulomb's bound μ|P_N| (μ = 0 for a law without Coulomb), then the signs of D_TE
/// and D_TA.
enum class AtlasMode : std::uint8_t {
  stick,     ///< |P_T| inside the bound (the law's own stick: D_TE = 0 for Newton's, z_T = 0 for
             ///< Frémond's, which leaves D_TE = −D_TA), or |D_TE| ≤ kAtlasStickTolerance · V.
  slide,     ///< at the bound, D_TE ≠ 0 with the sign of D_TA (or D_TA = 0): the slip goes on.
  reversal,  ///< at the bound, D_TE ≠ 0 against the sign of D_TA: the slip turns back.
  unknown,   ///< no converged answer.
};
std::string_view to_string(AtlasMode m);
AtlasMode atlas_mode_from_string(std::string_view s);

/// |D_TE| below this fraction of the contact speed V is a stick; |P_T| within this fraction of
/// μ|P_N| is at Coulomb's bound.
inline constexpr double kAtlasStickTolerance = 1e-9;

/// What is swept, under which laws. Defaults: the paper's bar's lower end, 200 × 200.
struct AtlasOptions {
  /// Laws by their law_names() (`newton`, `poisson`, `newton_coulomb`, `poisson_coulomb`,
  /// `fremond`, `stronge`, `stronge_coulomb`). `fremond` is the paper's §5 law: φ_N = k_N|z|^p/p
  /// and Coulomb on the mean tangential velocity with μ.
  std::vector<std::string> laws{"newton_coulomb", "poisson_coulomb", "fremond", "stronge_coulomb"};
  /// The law the others' distance is measured from; empty: laws[0].
  std::string reference;
  AtlasParameter parameter = AtlasParameter::mu;
  /// The swept parameter's values: μ ≥ 0, or e in [0, 1] (in (0, 1) when Frémond's k_N is
  /// calibrated); at least one.
  std::vector<double> values{1.0};
  double e = 0.9;          ///< e when μ is swept, in [0, 1].
  double mu = 1.0;         ///< μ when e is swept, ≥ 0.
  double fremond_p = 3.0;  ///< Frémond's normal exponent p > 1.
  /// Frémond's normal stiffness ≥ 0; 0: calibrated for each e as the paper's is (docs/concepts.md):
  /// the normal restitution −D_NE/D_NA is e at the scene's first impact from its initial state.
  double fremond_k_N = 0.0;
  /// The scene's contact (point, obstacle pair); −1: the first contact of the scene's first impact.
  int contact = -1;
  int theta_count = 200;                  ///< cells along θ, in [1, 100000].
  double theta_min = 0.0;                 ///< rad, finite.
  double theta_max = 1.5707963267948966;  ///< rad, > theta_min.
  int psi_count = 200;                    ///< cells along ψ, in [1, 100000].
  double psi_min = -3.141592653589793;    ///< rad, ≥ −π.
  double psi_max = 0.0;                   ///< rad, ≤ 0 and > psi_min.
  /// Spin ratios s = θ̇ r_g / V, finite; at least one (a third axis when several).
  std::vector<double> spins{0.0};
  /// Contact speed V = |(D_TA, D_NA)| > 0 (m/s); 0: the contact's speed at the scene's first
  /// impact.
  double speed = 0.0;
  int threads = 0;       ///< solve_batch's threads (0: one per core), ≥ 0.
  SolverOptions solver;  ///< every solve's options (check_uniqueness counts the solutions).
  /// Called on the calling thread after each block of points with (points done, points in all):
  /// the library prints nothing, a command shows it.
  std::function<void(std::size_t, std::size_t)> progress;

  /// Throws InvalidArgument naming the option (`laws[1]`, `values[0]`, `theta_count`, ...) and the
  /// reason. The scene-dependent checks (contact) are law_atlas's.
  void validate() const;
};

/// An atlas: its axes, and every point's answer as flat arrays, point (law, value, spin, θ, ψ) at
/// index(law, value, spin, θ, ψ) (ψ fastest). A value is NaN where the solve did not converge
/// (`status` says why), and `mode` is then unknown.
struct AtlasResult {
  std::vector<std::string> laws;
  std::string reference;  ///< the law of `distance`.
  AtlasParameter parameter = AtlasParameter::mu;
  std::vector<double> values;  ///< the swept parameter.
  double e = 0.0, mu = 0.0;    ///< the fixed ones (the swept one's is NaN).
  /// Frémond's k_N for each value (the same for every μ), NaN without Frémond in `laws`.
  std::vector<double> fremond_k_N;
  double fremond_p = 0.0;
  std::vector<double> spins, theta, psi;  ///< cell centres (rad).
  double speed = 0.0;                     ///< V (m/s).
  int contact = 0;
  double radius_of_gyration = 0.0;  ///< r_g = √(J/m) (m).

  // Per configuration, at config(spin, θ, ψ).
  std::vector<double> D_NA, D_TA;      ///< contact velocities before (m/s).
  std::vector<double> qdot_A;          ///< 3 per configuration (ẋ, ẏ, θ̇).
  std::vector<double> kinetic_energy;  ///< T_A (J).

  // Per point.
  std::vector<double> energy_ratio;  ///< (T_E − T_A)/T_A.
  /// ‖q̇_E − q̇_E,reference‖_M / ‖q̇_A‖_M, the norm of kinetic energy (so units do not mix).
  std::vector<double> distance;
  std::vector<double> P_N, P_T, D_NE, D_TE;
  std::vector<double> qdot_E;            ///< 3 per point.
  std::vector<std::uint8_t> admissible;  ///< the certificate holds (1) or not (0).
  std::vector<std::uint8_t> failed;      ///< Inequality: the first that fails.
  std::vector<std::uint8_t> status;      ///< SolverStatus.
  std::vector<std::uint8_t> mode;        ///< AtlasMode.
  /// Solutions: 0 none (no_solution), 1 unique, n ≥ 2 found (2: several, not counted), −1 unknown
  /// (not converged).
  std::vector<std::int8_t> solutions;

  std::size_t configurations() const { return spins.size() * theta.size() * psi.size(); }
  std::size_t points() const { return laws.size() * values.size() * configurations(); }
  std::size_t config(std::size_t spin, std::size_t th, std::size_t ps) const {
    return (spin * theta.size() + th) * psi.size() + ps;
  }
  std::size_t index(std::size_t law, std::size_t value, std::size_t spin, std::size_t th,
                    std::size_t ps) const {
    return (law * values.size() + value) * configurations() + config(spin, th, ps);
  }
};

/// The one-contact impact problem of configuration (θ, ψ, s) of contact `contact` of a validated
/// scene at contact speed V: M, W_N, W_T of kinematics.hpp, q̇_A as the file says.
/// Throws InvalidArgument naming `contact`, `speed` or a non-finite angle.
SmallImpactProblem atlas_problem(const Scene& scene, int contact, double theta, double psi,
                                 double spin, double speed);

/// Sweeps the scene (validated: Scene::validate) as `options` say. Throws InvalidArgument naming
/// the option, before any solve.
AtlasResult law_atlas(const Scene& scene, const AtlasOptions& options = {});

}  // namespace fremond
