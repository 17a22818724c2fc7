// fit_law: a law family's parameters from measured impacts (docs/measurements.md#fit).
//
// The search runs in the unit box: each fitted parameter is mapped from u ∈ [0, 1], linearly
// (e, μ, p) or logarithmically (the stiffnesses, which span decades). Frémond's stiffnesses are
// searched relative to the data's own scale, k = ratio · m v^(2−p) (m the contact's effective
// mass 1/(W_Nᵀ M⁻¹ W_N), v the typical approach speed), since k's units depend on p: a box of
// ratios holds the same restitutions whatever p is, where a box of k would not.
#include "fremond/fit/fit_law.hpp"

#include <nlopt.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>

#include "fit/detail/impact_set.hpp"
#include "fremond/core/error.hpp"

namespace fremond {

namespace {

using Clock = std::chrono::steady_clock;

// What the data say about the scale of Frémond's stiffnesses.
struct Scales {
  double m_N = 1.0;  // median effective mass of the first contact, normal
  double m_T = 1.0;  // the same, tangential
  double v = 1.0;    // median approach speed |D_NA| of the first contact
};

double median(std::vector<double> v, double otherwise) {
  if (v.empty()) return otherwise;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

Scales scales_of(std::span<const MeasuredImpact> impacts) {
  std::vector<double> mN, mT, v;
  for (const MeasuredImpact& m : impacts) {
    const ImpactProblem& pb = m.problem;
    const Eigen::LDLT<MatrixX> ldlt(pb.M);
    const VectorX wn = pb.W_N.col(0);
    mN.push_back(1.0 / wn.dot(ldlt.solve(wn)));
    if (pb.has_tangential()) {
      const VectorX wt = pb.W_T.col(0);
      mT.push_back(1.0 / wt.dot(ldlt.solve(wt)));
    }
    const double d = wn.dot(pb.qdot_A) + (pb.w_N.size() ? pb.w_N(0) : 0.0);
    if (d < 0.0) v.push_back(-d);
  }
  Scales s;
  s.m_N = median(mN, 1.0);
  s.m_T = median(mT, s.m_N);
  s.v = median(v, 1.0);
  if (!(s.v > 0.0) || !std::isfinite(s.v)) s.v = 1.0;
  return s;
}

// One fitted parameter: its search interval and how u maps onto it.
struct Parameter {
  std::string name;
  double lower = 0.0, upper = 1.0;
  bool log_scale = false;
  // Searched as a ratio of m v^(2−x), x the exponent named here ("p" for k, "q" for k_T).
  std::string relative_to;
  // The natural domain, where a finite difference may step: [min, max].
  double min = 0.0, max = std::numeric_limits<double>::infinity();
  bool open_min = false;
};

Parameter default_parameter(const std::string& name) {
  Parameter p;
  p.name = name;
  if (name == "e") {
    p.lower = 0.0, p.upper = 1.0, p.max = 1.0;
  } else if (name == "mu") {
    p.lower = 0.0, p.upper = 2.0;  // beyond μ = 2 every contact of everyday data sticks
  } else if (name == "p") {
    p.lower = 1.1, p.upper = 5.0, p.min = 1.0, p.open_min = true;
  } else if (name == "k") {
    // ratio 0.1: ε = 0 (k < 2m at p = 2, eq. 24); 1e4: ε = 0.9996.
    p.lower = 0.1, p.upper = 1e4, p.log_scale = true, p.relative_to = "p";
  } else if (name == "k_T") {
    p.lower = 1e-3, p.upper = 1e3, p.log_scale = true, p.relative_to = "q";
  }
  return p;
}

// The family's search space: the fitted parameters, those held, the map from the unit box.
struct Space {
  LawFamily family;
  std::vector<Parameter> params;  // every fitted parameter of the family
  std::vector<int> free;          // the indices of those searched
  std::map<std::string, double> held;
  Scales s;

  double value_of(const std::string& name, const VectorX& values) const {
    for (std::size_t i = 0; i < params.size(); ++i)
      if (params[i].name == name) return values(static_cast<Eigen::Index>(i));
    return held.at(name);
  }

  // The fitted parameters' values at u (one entry per free parameter).
  VectorX values(const double* u) const {
    VectorX v(static_cast<Eigen::Index>(params.size()));
    for (std::size_t i = 0; i < params.size(); ++i) {
      const auto it = held.find(params[i].name);
      v(static_cast<Eigen::Index>(i)) = it != held.end() ? it->second : std::nan("");
    }
    const auto map = [](const Parameter& p, double x) {
      x = std::clamp(x, 0.0, 1.0);
      return p.log_scale ? std::exp(std::log(p.lower) + x * (std::log(p.upper) - std::log(p.lower)))
                         : p.lower + x * (p.upper - p.lower);
    };
    // Linear and absolute ones first: a relative stiffness needs its exponent.
    for (std::size_t f = 0; f < free.size(); ++f) {
      const Parameter& p = params[static_cast<std::size_t>(free[f])];
      if (p.relative_to.empty()) v(free[f]) = map(p, u[f]);
    }
    for (std::size_t f = 0; f < free.size(); ++f) {
      const Parameter& p = params[static_cast<std::size_t>(free[f])];
      if (p.relative_to.empty()) continue;
      const double m = p.name == "k" ? s.m_N : s.m_T;
      v(free[f]) = map(p, u[f]) * m * std::pow(s.v, 2.0 - value_of(p.relative_to, v));
    }
    return v;
  }

  std::map<std::string, double> named(const VectorX& values) const {
    std::map<std::string, double> out = held;
    for (std::size_t i = 0; i < params.size(); ++i)
      out[params[i].name] = values(static_cast<Eigen::Index>(i));
    return out;
  }

  ImpactLaw law(const VectorX& values) const { return make_law(family, named(values)); }
};

Space make_space(LawFamily family, const FitOptions& o, std::span<const MeasuredImpact> impacts) {
  Space sp;
  sp.family = family;
  sp.s = scales_of(impacts);
  sp.held = held_parameters(family);
  const auto names = fitted_parameters(family);
  const auto known = [&](const std::string& n) {
    return std::find(names.begin(), names.end(), n) != names.end() || sp.held.count(n) > 0;
  };
  const auto list = [&] {
    std::string l;
    for (const auto& n : names) l += (l.empty() ? "" : ", ") + n;
    for (const auto& [n, v] : held_parameters(family)) l += ", " + n;
    return l;
  };
  for (const auto& [name, value] : o.fixed) {
    if (!known(name))
      throw InvalidArgument(
          "fixed." + name,
          "is not a parameter of " + std::string(to_string(family)) + " (" + list() + ")");
    sp.held[name] = value;
  }
  for (const auto& n : names) sp.params.push_back(default_parameter(n));
  for (const auto& [name, b] : o.bounds) {
    const std::string& wanted = name;  // clang 14 cannot capture a structured binding
    auto it = std::find_if(sp.params.begin(), sp.params.end(),
                           [&](const Parameter& p) { return p.name == wanted; });
    if (it == sp.params.end())
      throw InvalidArgument(
          "bounds." + name,
          "is not a fitted parameter of " + std::string(to_string(family)) + " (" + list() + ")");
    if (b.first < it->min || b.second > it->max || (it->open_min && b.first <= it->min))
      throw InvalidArgument("bounds." + name, "must lie in the parameter's domain");
    if (it->log_scale && !(b.first > 0.0))
      throw InvalidArgument("bounds." + name, "must be > 0: the stiffness is searched in decades");
    it->lower = b.first;
    it->upper = b.second;
    it->relative_to.clear();  // the user's bounds are the stiffness itself
  }
  for (std::size_t i = 0; i < sp.params.size(); ++i)
    if (!sp.held.count(sp.params[i].name)) sp.free.push_back(static_cast<int>(i));
  // The held values are checked where the law is made: the middle of the box must be a law.
  std::vector<double> mid(sp.free.size(), 0.5);
  (void)sp.law(sp.values(mid.data()));
  return sp;
}

double loss(FitLoss kind, double s, double r) {
  // A solve with no velocity weighs as a miss by 1000 sigmas: large, finite, so that NLopt goes on.
  if (!std::isfinite(r)) r = 1e3;
  const double a = std::fabs(r);
  switch (kind) {
    case FitLoss::least_squares:
      return r * r;
    case FitLoss::huber:
      return a <= s ? r * r : 2.0 * s * a - s * s;
    case FitLoss::soft_l1:
      return 2.0 * s * s * (std::sqrt(1.0 + (r / s) * (r / s)) - 1.0);
  }
  return r * r;
}

// The objective over one set of impacts, in the unit box.
struct Objective {
  Objective(const Space* sp, const detail::ImpactSet* s, const FitOptions* opt)
      : space(sp), set(s), o(opt) {}
  const Space* space;
  const detail::ImpactSet* set;
  const FitOptions* o;
  int evaluations = 0;
  std::vector<double> r;
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> best_u;

  double operator()(const double* u) {
    ++evaluations;
    const ImpactLaw law = space->law(space->values(u));
    set->residuals(law, o->solver, o->batch, r);
    double f = 0.0;
    for (const double x : r) f += loss(o->loss, o->loss_scale, x);
    if (f < best) {
      best = f;
      best_u.assign(u, u + space->free.size());
    }
    return f;
  }
  static double call(unsigned /*n*/, const double* u, double* /*grad*/, void* data) {
    return (*static_cast<Objective*>(data))(u);
  }
};

// One NLopt stage over the unit box from u (updated to the best point seen); its nlopt_result.
int run_stage(nlopt_algorithm algorithm, Objective& f, std::vector<double>& u, int evaluations,
              double xtol_rel, double step) {
  const auto n = static_cast<unsigned>(u.size());
  nlopt_opt opt = nlopt_create(algorithm, n);
  if (!opt) throw InvalidArgument("fit", "NLopt could not create its optimiser");
  const std::vector<double> lo(n, 0.0), hi(n, 1.0);
  nlopt_set_lower_bounds(opt, lo.data());
  nlopt_set_upper_bounds(opt, hi.data());
  nlopt_set_min_objective(opt, &Objective::call, &f);
  nlopt_set_maxeval(opt, evaluations);
  if (xtol_rel > 0.0) {
    nlopt_set_xtol_rel(opt, xtol_rel);
    nlopt_set_xtol_abs1(opt, xtol_rel);  // u near 0 (e = 0, μ = 0): a relative step never ends
  }
  if (step > 0.0) nlopt_set_initial_step1(opt, step);
  double value = 0.0;
  const nlopt_result code = nlopt_optimize(opt, u.data(), &value);
  nlopt_destroy(opt);
  if (!f.best_u.empty()) u = f.best_u;
  return static_cast<int>(code);
}

// The local polish from u: BOBYQA (a quadratic model within the box); for one parameter, where
// NLopt's BOBYQA has no room for its model, Nelder-Mead.
int polish(Objective& f, std::vector<double>& u, const FitOptions& o) {
  if (u.empty()) {
    f(u.data());
    return NLOPT_SUCCESS;
  }
  for (double& x : u) x = std::clamp(x, 0.0, 1.0);
  const int code = run_stage(u.size() >= 2 ? NLOPT_LN_BOBYQA : NLOPT_LN_NELDERMEAD, f, u,
                             o.local_evaluations, o.xtol_rel, 0.05);
  return code;
}

struct Stages {
  std::vector<double> u;
  int global_status = 0, local_status = 0, evaluations = 0;
};

Stages search(const Space& sp, const detail::ImpactSet& set, const FitOptions& o,
              const std::vector<double>* start) {
  Objective f{&sp, &set, &o};
  Stages out;
  out.u = start ? *start : std::vector<double>(sp.free.size(), 0.5);
  if (!start && o.global_evaluations > 0 && !sp.free.empty())
    out.global_status = run_stage(NLOPT_GN_DIRECT_L, f, out.u, o.global_evaluations, 0.0, 0.0);
  out.local_status = polish(f, out.u, o);
  out.evaluations = f.evaluations;
  return out;
}

// The Jacobian of the weighted residuals in the free parameters' own values, by central
// differences where the parameter's domain allows, one-sided at its edge.
MatrixX jacobian(const Space& sp, const detail::ImpactSet& set, const FitOptions& o,
                 const VectorX& values, const std::vector<double>& r0, int& evaluations) {
  MatrixX J(static_cast<Eigen::Index>(r0.size()), static_cast<Eigen::Index>(sp.free.size()));
  std::vector<double> rp, rm;
  for (std::size_t f = 0; f < sp.free.size(); ++f) {
    const int i = sp.free[f];
    const Parameter& p = sp.params[static_cast<std::size_t>(i)];
    const double x = values(i);
    const double h = 1e-6 * std::max(std::fabs(x), p.log_scale ? 1e-12 : 1.0);
    const bool up = x + h <= p.max, down = p.open_min ? x - h > p.min : x - h >= p.min;
    VectorX vp = values, vm = values;
    if (up) vp(i) = x + h;
    if (down) vm(i) = x - h;
    set.residuals(sp.law(vp), o.solver, o.batch, rp);
    set.residuals(sp.law(vm), o.solver, o.batch, rm);
    evaluations += 2;
    const double width = vp(i) - vm(i);
    for (std::size_t k = 0; k < r0.size(); ++k) {
      const double d = (rp[k] - rm[k]) / width;
      J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(f)) = std::isfinite(d) ? d : 0.0;
    }
  }
  return J;
}

// s² (JᵀJ)⁻¹'s diagonal, square-rooted; +∞ for a parameter with a share in a direction the data
// do not see (an eigenvalue of JᵀJ below 1e-12 of the largest).
VectorX gauss_newton(const MatrixX& J, double s2) {
  const auto d = J.cols();
  VectorX sd = VectorX::Zero(d);
  if (d == 0) return sd;
  const Eigen::SelfAdjointEigenSolver<MatrixX> eig(J.transpose() * J);
  const VectorX& lambda = eig.eigenvalues();
  const MatrixX& V = eig.eigenvectors();
  const double top = lambda.maxCoeff();
  for (Eigen::Index k = 0; k < d; ++k) {
    const bool blind = !(top > 0.0) || lambda(k) <= 1e-12 * top;
    for (Eigen::Index i = 0; i < d; ++i) {
      if (blind) {
        if (std::fabs(V(i, k)) > 1e-6) sd(i) = std::numeric_limits<double>::infinity();
      } else {
        sd(i) += V(i, k) * V(i, k) / lambda(k);
      }
    }
  }
  for (Eigen::Index i = 0; i < d; ++i) sd(i) = std::sqrt(s2 * sd(i));
  return sd;
}

// The folds' and the bootstrap's draws: Fisher-Yates on a 64-bit Mersenne twister, written out so
// that a seed gives the same folds with every standard library.
std::vector<int> shuffled(int n, std::mt19937_64& rng) {
  std::vector<int> idx(static_cast<std::size_t>(n));
  std::iota(idx.begin(), idx.end(), 0);
  for (int i = n - 1; i > 0; --i)
    std::swap(idx[static_cast<std::size_t>(i)],
              idx[static_cast<std::size_t>(rng() % static_cast<std::uint64_t>(i + 1))]);
  return idx;
}

std::string status_name(int code) {
  return code == 0 ? "not_run" : nlopt_result_to_string(static_cast<nlopt_result>(code));
}

double sum_squares(const std::vector<double>& r, int* counted) {
  double s = 0.0;
  int c = 0;
  for (const double x : r)
    if (std::isfinite(x)) s += x * x, ++c;
  if (counted) *counted = c;
  return s;
}

}  // namespace

FitResult fit_law(std::span<const MeasuredImpact> impacts, LawFamily family,
                  const FitOptions& options) {
  const auto t0 = Clock::now();
  options.validate();
  validate(impacts);
  const int n = static_cast<int>(impacts.size());
  if (options.folds > n)
    throw InvalidArgument("folds", "must be at most the number of impacts (" + std::to_string(n) +
                                       "), got " + std::to_string(options.folds));
  const Space sp = make_space(family, options, impacts);
  const detail::ImpactSet all(impacts);

  FitResult out;
  out.family = family;
  const Stages best = search(sp, all, options, nullptr);
  out.global_status = best.global_status;
  out.local_status = best.local_status;
  out.status = status_name(best.local_status);
  out.evaluations = best.evaluations;
  const VectorX full = sp.values(best.u.data());
  out.law = sp.law(full);
  for (const int i : sp.free) {
    out.names.push_back(sp.params[static_cast<std::size_t>(i)].name);
  }
  out.values.resize(static_cast<Eigen::Index>(sp.free.size()));
  for (std::size_t f = 0; f < sp.free.size(); ++f)
    out.values(static_cast<Eigen::Index>(f)) = full(sp.free[f]);

  std::vector<double> r;
  out.failed_solves = all.residuals(out.law, options.solver, options.batch, r);
  out.objective = 0.0;
  for (const double x : r) out.objective += loss(options.loss, options.loss_scale, x);
  int counted = 0;
  const double ss = sum_squares(r, &counted);
  out.measured = all.measured();
  out.training_rms = counted > 0 ? std::sqrt(ss / counted) : std::nan("");

  // Uncertainties.
  const auto d = static_cast<int>(sp.free.size());
  if (options.uncertainty == FitUncertainty::gauss_newton) {
    const MatrixX J = jacobian(sp, all, options, full, r, out.fold_evaluations);
    const double s2 = options.absolute_sigma ? 1.0
                      : counted > d          ? ss / (counted - d)
                                             : std::numeric_limits<double>::infinity();
    out.uncertainties = gauss_newton(J, s2);
  } else {
    std::mt19937_64 rng(options.seed ^ 0x9e3779b97f4a7c15ULL);
    MatrixX draws(options.bootstrap_samples, d);
    for (int b = 0; b < options.bootstrap_samples; ++b) {
      std::vector<int> idx(static_cast<std::size_t>(n));
      for (int& i : idx) i = static_cast<int>(rng() % static_cast<std::uint64_t>(n));
      const detail::ImpactSet resample(impacts, idx);
      const Stages s = search(sp, resample, options, &best.u);
      out.fold_evaluations += s.evaluations;
      const VectorX v = sp.values(s.u.data());
      for (int f = 0; f < d; ++f) draws(b, f) = v(sp.free[static_cast<std::size_t>(f)]);
    }
    out.uncertainties.resize(d);
    for (int f = 0; f < d; ++f) {
      const double mean = draws.col(f).mean();
      out.uncertainties(f) =
          std::sqrt((draws.col(f).array() - mean).square().sum() / (options.bootstrap_samples - 1));
    }
  }

  // k-fold cross-validation: each fold's impacts predicted by the law fitted on the others,
  // polished from the optimum on every impact (the global stage is not repeated: its box is the
  // same and its best point a start, which the fold's own data then move).
  out.heldout_rms = std::nan("");
  if (options.folds >= 2) {
    std::mt19937_64 rng(options.seed);
    const std::vector<int> order = shuffled(n, rng);
    double held_ss = 0.0;
    int held_count = 0;
    for (int k = 0; k < options.folds; ++k) {
      std::vector<int> train, test;
      for (int i = 0; i < n; ++i)
        (i * options.folds / n == k ? test : train).push_back(order[static_cast<std::size_t>(i)]);
      const detail::ImpactSet train_set(impacts, train), test_set(impacts, test);
      const Stages s = search(sp, train_set, options, &best.u);
      out.fold_evaluations += s.evaluations;
      std::vector<double> rt;
      test_set.residuals(sp.law(sp.values(s.u.data())), options.solver, options.batch, rt);
      int c = 0;
      held_ss += sum_squares(rt, &c);
      held_count += c;
    }
    out.heldout_rms = held_count > 0 ? std::sqrt(held_ss / held_count) : std::nan("");
  }
  out.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

std::vector<FitResult> fit_laws(std::span<const MeasuredImpact> impacts,
                                const std::vector<LawFamily>& families, const FitOptions& options) {
  if (families.empty()) throw InvalidArgument("law", "needs at least one law family");
  std::vector<FitResult> out;
  for (const LawFamily f : families) out.push_back(fit_law(impacts, f, options));
  // The held-out error ranks (the training error without folds); a law with no finite error last.
  const auto key = [&options](const FitResult& r) {
    const double e = options.folds >= 2 ? r.heldout_rms : r.training_rms;
    return std::isfinite(e) ? e : std::numeric_limits<double>::infinity();
  };
  std::stable_sort(out.begin(), out.end(),
                   [&](const FitResult& a, const FitResult& b) { return key(a) < key(b); });
  return out;
}

}  // namespace fremond
