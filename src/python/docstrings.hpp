#pragma once
// Every docstring of the Python module, in one place, so the bindings stay a list of names and the
// documentation reads as one text. Each restates the C++ header it binds (the headers are the
// manual); equation numbers are the paper's, conventions in docs/.

namespace fremond::python::doc {

inline constexpr const char* kModule = R"doc(
fremond: impact laws of rigid bodies (Newton, Poisson, Coulomb, Frémond), after Cataldo &
Sampaio's comparison on a falling bar.

Problems, laws and potentials go in as NumPy arrays and Python objects; every answer comes back
with its thermodynamic admissibility certificate (docs/concepts.md: (15) total and per contact, (17)
reaction, (19) dissipation, the Fenchel-Young gap). The module is a thin layer over the C++
library: each function here calls the library function of the same name.

Main entry points:
  solve_impact(problem, law)            one impact (docs/concepts.md and docs/laws.md)
  simulate(scene, options)              a scene's motion: trajectory, energy and impact log
  normal_restitution_curve(...)         data of the paper's Fig. 8
  tangential_curve(...)                 data of the paper's Fig. 9
  paper_bar_scene(PaperLaw.newton)      the paper's bar with one of its five laws
and the plotting helpers in fremond.plots.
)doc";

// ---- enums
inline constexpr const char* kEnumFromString =
    "The value named by its text (the same names as the problem file and the command line); "
    "raises ValueError naming the accepted values.";
inline constexpr const char* kTangentialLaw =
    "Frémond's tangential law: none, potential (e.g. the viscous dead zone, eq. 25) or coulomb "
    "(on the mean tangential velocity, bound mu|P_N|).";
inline constexpr const char* kSolverStatus = "How a solve ended (converged, max_iterations, ...).";
inline constexpr const char* kSolverMethod = "Which method produced an answer, or the one to use.";
inline constexpr const char* kStopCriterion = "Which stopping criterion fired.";
inline constexpr const char* kInequality =
    "The first admissibility inequality that failed (none, total_15, per_contact_15, reaction_17, "
    "dissipation_19, complementarity_16, fenchel_young, non_penetration).";
inline constexpr const char* kScaling =
    "Which constants a curve's parameters are written in: library (potentials of the mean "
    "velocity) "
    "or paper (k_paper = k 2^(1-p), k_T,paper = k_T 2^(1-q), r_paper = 2r; docs/laws.md).";
inline constexpr const char* kPaperLaw =
    "The five laws the paper compares on the bar (the paper's Fig. 1), and Stronge + Coulomb.";
inline constexpr const char* kIntegrator = "event_driven (exact flights) or moreau_jean.";
inline constexpr const char* kPhase = "The phase of a run: event_driven or moreau_jean.";
inline constexpr const char* kSimulationStatus = "How a run ended.";
inline constexpr const char* kImpactKind =
    "What produced an impact-log entry: event, time_step or accumulation.";

// ---- potentials
inline constexpr const char* kInterval =
    "A closed interval [lo, hi]; empty when lo > hi (a subdifferential outside the domain).";
inline constexpr const char* kCapabilities =
    "What a potential can do, so the solver picks the cheapest exact method it allows.";
inline constexpr const char* kPotential = R"doc(
A convex pseudo-potential of dissipation phi of one contact's mean velocity z (paper §5.2,
docs/laws.md): non-negative, zero at the origin. The impact law is -P in d phi(z).

Public interface: value, subgradient, subdifferential, prox, conjugate, fenchel_young_gap,
describe, clone, capabilities.

To write your own in Python, subclass Potential and override the hooks (non-virtual interface,
as in C++):
    do_value(z) -> float                     required
    do_subgradient(z) -> float               required
    do_subdifferential(z) -> (lo, hi)        optional: allows the exact prox by bisection
    do_prox(x, tau) -> (y, dy)               optional: prox_{tau phi}(x) and its derivative
    do_conjugate(s) -> float                 optional: the Fenchel-Young certificate
    do_name() -> str                         optional (default: the class name)
    do_describe() -> str                     optional
The capabilities follow from the hooks defined. Call Potential.__init__(self) in __init__.
A Python potential is slower than a C++ one (each call crosses into Python) but works anywhere
a potential does: in laws, solve_impact, simulate, check_potential.
)doc";
inline constexpr const char* kValue = "phi(z); +inf outside the domain.";
inline constexpr const char* kSubgradient = "One element of the subdifferential at z.";
inline constexpr const char* kSubdifferential = "The subdifferential at z as an Interval.";
inline constexpr const char* kProx =
    "prox_{tau phi}(x) = argmin_y phi(y) + (y - x)^2/(2 tau), tau > 0. With derivative=True "
    "returns (y, dy) with dy an element of the Clarke derivative, in [0, 1].";
inline constexpr const char* kConjugate =
    "phi*(s) = sup_z s z - phi(z); raises ValueError when the conjugate is not known.";
inline constexpr const char* kFenchelYoung =
    "phi(z) + phi*(s) - s z >= 0, zero exactly when s is in d phi(z); NaN without a conjugate.";
inline constexpr const char* kDescribe = "One line naming the kind and its parameters.";
inline constexpr const char* kClone = "A copy with the same parameters.";
inline constexpr const char* kPower =
    "PowerPotential(k, p): phi(z) = k|z|^p/p, k >= 0, p > 1 (eq. 22 in the library's scaling).";
inline constexpr const char* kDeadZone =
    "DeadZonePowerPotential(k, q, r): phi(y) = (k/q) max(0, |y| - r)^q, the viscous dead zone "
    "(eq. 25 in the library's scaling; the paper's k_T,paper = k 2^(1-q), r_paper = 2r).";
inline constexpr const char* kAbsoluteValue =
    "AbsoluteValuePotential(b): b|y|, Coulomb's dissipation with a fixed bound b = mu P_N.";
inline constexpr const char* kIndicator =
    "IndicatorPotential(nonpositive=False): the indicator of R+ (or R-), the reaction of eq. 16.";
inline constexpr const char* kSum = "SumPotential(f, g): f + g (also f + g in Python).";
inline constexpr const char* kScaled = "ScaledPotential(alpha, f): alpha f, alpha > 0.";
inline constexpr const char* kRegistry =
    "Named potential kinds, as the problem file makes them. with_builtins() holds power, "
    "deadzone_power, absolute_value, indicator_nonnegative, indicator_nonpositive.";
inline constexpr const char* kRegistryAdd =
    "add(name, make, required=[], optional={}, description=''): a new kind; make(params: dict) "
    "returns a Potential (a Python one too).";
inline constexpr const char* kRegistryMake =
    "make(name, params: dict, where='potential'): a potential of that kind; refuses unknown and "
    "missing parameters.";
inline constexpr const char* kConformanceOptions =
    "Options of check_potential: sample range and count, prox steps, tolerance, seed.";
inline constexpr const char* kConformanceReport =
    "What check_potential found: ok, failures (sentences with numbers), and the largest errors.";
inline constexpr const char* kCheckPotential = R"doc(
Checks the invariants every pseudo-potential must satisfy before it is trusted inside an impact
law: phi(0) = 0 and phi >= 0; convexity along chords; the subgradient inequality; prox optimality;
firm non-expansiveness of the prox and its derivative in [0, 1]; and, with a conjugate,
Fenchel-Young >= 0, = 0 at prox points, and Moreau's identity.
)doc";

// ---- laws, problems, results
inline constexpr const char* kImpactLaw = R"doc(
An impact law with its parameters (docs/laws.md). Build it with the named constructors:
  ImpactLaw.newton(e), ImpactLaw.poisson(e), ImpactLaw.newton_coulomb(e, mu),
  ImpactLaw.poisson_coulomb(e, mu), ImpactLaw.fremond(normal, tangential=None),
  ImpactLaw.fremond_coulomb(normal, mu).
e and mu are a number or a list with one value per contact; potentials are one Potential or a
list with one per contact.
)doc";
inline constexpr const char* kLawValidate =
    "Checks the parameters against the number of contacts; raises ValueError naming law.e, "
    "law.mu, law.normal or law.tangential.";
inline constexpr const char* kImpactProblem = R"doc(
ImpactProblem(M, W_N, qdot_A, W_T=None, w_N=None, w_T=None): one impact (docs/concepts.md),
M (qdot_E - qdot_A) = W_N P_N + W_T P_T, contact velocities D = W^T qdot + w. W_N and W_T are
n x c (one column a contact); without W_T the problem is frictionless. Checked on construction:
sizes, finite numbers, M symmetric positive definite (ValueError naming the member).
)doc";
inline constexpr const char* kSolverOptions =
    "Options of the impact solvers (method, tolerance, iteration budgets, admissibility "
    "tolerance, check_uniqueness); the solver never writes into them.";
inline constexpr const char* kSolverReport =
    "How the solver ended: method, status, criterion, message, iterations, residual.";
inline constexpr const char* kAdmissibility = R"doc(
The admissibility certificate of one impact (docs/concepts.md; eqs. 9, 15-19): kinetic_energy_A,
energy_change = T_E - T_A, total = -P.z (15), per_contact, reaction (17), dissipation (19),
complementarity (16), penetration, fenchel_young_gap, admissible, failed (the first inequality
violated), failed_contact, violation.
)doc";
inline constexpr const char* kImpactResult =
    "The result of one impact: qdot_E, percussions P_N, P_T (on the body), contact velocities "
    "D_NA, D_TA, D_NE, D_TE, energy_change, admissibility, unique, solver; ok() when converged.";
inline constexpr const char* kSolveImpact = R"doc(
solve_impact(problem, law, options=SolverOptions()) -> ImpactResult

Solves one impact with any law: validate, closed form, Newton, proximal, NLopt, then the
admissibility certificate. Raises ValueError for an invalid problem, law or options; a solver that
does not converge says so in result.solver.status. Contacts that G = W^T M^-1 W does not couple
(two bodies in one problem) are solved group by group, each to its own velocity scale.
)doc";
inline constexpr const char* kImpactSolver = R"doc(
ImpactSolver(problem, law, options=SolverOptions())

A solver prepared for one configuration: built once from the problem (M, W_N, W_T, w_N, w_T and
a first qdot_A), the law and the options, which it validates; then solve(qdot_A) as often as
wanted, and update(M, W_N, W_T, w_N, w_T) or update_law(law) between configurations. Every answer
is solve_impact's on the same data, to the last bit; a solve checks only the new velocity. Raises
ValueError naming the member on bad input, and then keeps its previous state.
)doc";
inline constexpr const char* kSolveImpactAll =
    "Every solution found (mode enumeration for laws with friction on small problems); an empty "
    "list means the law has no solution for these data.";
inline constexpr const char* kCheckAdmissibility =
    "The docs/concepts.md certificate of any answer (e.g. one you computed yourself).";
inline constexpr const char* kLawResidual =
    "The law's scaled natural-map residual at an answer: zero exactly when it satisfies the law.";
inline constexpr const char* kParseProblem =
    "parse_problem_file(text, registry=None) -> (problem, law): reads an impact-problem file "
    "(docs/problem-file.md, JSON text).";
inline constexpr const char* kResultToJson =
    "result_to_json(result, indent=-1): the JSON form of a result (as `fremond impact` prints).";

// ---- scenes and simulation
inline constexpr const char* kContactPoint =
    "A point of the body frame that can touch (radius >= 0).";
inline constexpr const char* kPlanarBody = "Mass, centroidal inertia and contact points.";
inline constexpr const char* kHalfPlane = "The fixed half-plane {p : normal.p >= offset}.";
inline constexpr const char* kPlanarState = "q = (x, y, theta) and qdot.";
inline constexpr const char* kScene =
    "A planar rigid body, its obstacles, gravity, initial state and impact law; contact k is "
    "point k // len(obstacles), obstacle k % len(obstacles).";
inline constexpr const char* kBarParameters =
    "The paper's bar: mass 1 kg, half_length 0.5 m (docs/laws.md), gravity 9.81, the initial state "
    "of paper §3 (x 0, xdot 2, y 1, theta pi/4).";
inline constexpr const char* kPaperBarScene =
    "paper_bar_scene(law: PaperLaw, bar=BarParameters()): the paper's scene with one of its laws, "
    "Frémond's k_N calibrated so that the first impact's normal restitution is 0.9 (docs/laws.md).";
inline constexpr const char* kPaperLawFn =
    "paper_law(law: PaperLaw, k_N): the law with the paper's parameters (the paper's Fig. 1).";
inline constexpr const char* kPaperStiffness =
    "paper_bar_normal_stiffness(bar=BarParameters()): docs/laws.md's k_N (about 85.36 for p = 3).";
inline constexpr const char* kEnergy =
    "Total energy 1/2 qdot^T M qdot + m g y (the paper's Fig. 1).";
inline constexpr const char* kSimulationOptions =
    "Options of simulate: integrator, t_end, step, max_impacts, tolerances, sample_interval, "
    "solver (SolverOptions).";
inline constexpr const char* kImpactRecord =
    "One entry of the impact log: time, kind, contacts, velocities and percussions of the "
    "contacts of the impact, energy_A and energy_E (total energy just before and after), "
    "admissible, failed, solver.";
inline constexpr const char* kSimulationResult =
    "The summary of a run: status, message, impacts, inadmissible_impacts, energies, ...";
inline constexpr const char* kSimulation = R"doc(
A recorded run: result (SimulationResult), the trajectory samples t, q (N x 3), qdot (N x 3),
energy, phase (arrays, one row a sample; an impact gives two samples at the same time, just before
and just after), impacts (the impact log) and phase_changes [(t, from, to, why)].
)doc";
inline constexpr const char* kSimulate = R"doc(
simulate(scene, options=SimulationOptions()) -> Simulation

Runs the scene: exact flights and every impact with the scene's law, accumulations and persistent
contact handed to Moreau-Jean. Records every sample and impact. Raises ValueError for an invalid
scene or options.
)doc";
inline constexpr const char* kParseScene =
    "parse_scene_file(text, registry=None) -> (scene, options): reads a scene file (JSON text).";
inline constexpr const char* kContactFrame =
    "contact_frame(scene, contact, q) -> (gap, W_N, W_T) of one contact at configuration q.";

// ---- curves
inline constexpr const char* kNormalCurveParameters =
    "Fig. 8: NormalCurveParameters(mass=1, k=4, p=2, scaling=Scaling.library).";
inline constexpr const char* kTangentialCurveParameters =
    "Fig. 9: TangentialCurveParameters(mass, k_N, p, D_NA, k_T, q, r, scaling); the defaults are "
    "the paper's Fig. 9 in the library's scaling (k_T 1.5, q 2, r 0.2; paper k_T 0.75, r 0.4).";
inline constexpr const char* kCurve = R"doc(
A curve as NumPy arrays, one entry an impact of the point mass: D_NA, D_NE, D_TA, D_TE, P_N,
P_N_reaction, P_T, energy_change, in_dead_zone, admissible, failed (list of Inequality), status
(list of SolverStatus), and the parameters it was computed with.
)doc";
inline constexpr const char* kNormalCurve = R"doc(
normal_restitution_curve(parameters, speeds, options=SolverOptions()) -> Curve

Fig. 8: one impact of a point mass per approach speed |D_NA| >= 0 under Frémond's normal law
phi_N = k|z|^p/p alone (solve_impact on the point-mass problem).
)doc";
inline constexpr const char* kTangentialCurve = R"doc(
tangential_curve(parameters, D_TA, options=SolverOptions()) -> Curve

Fig. 9: one impact per tangential velocity D_TA under Frémond's law with the viscous dead zone
(eq. 25), the normal law fixed. Inside the dead zone |D_TA| <= r, D_TE = D_TA.
)doc";
inline constexpr const char* kEquivalentRestitution =
    "Eq. (24): for p = 2, epsilon = (k - 2m)/(k + 2m) in the library's scaling (negative: the mass "
    "stops, D_NE = 0). Raises ValueError unless p = 2.";
inline constexpr const char* kPointMassProblem =
    "point_mass_problem(mass, D_NA, D_TA=None): the point-mass problem of Figs. 8 and 9.";

}  // namespace fremond::python::doc
