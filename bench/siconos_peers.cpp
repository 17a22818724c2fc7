// Siconos peers of our solvers (see siconos_peers.hpp). Built as C++17 against Siconos Numerics and
// Kernel, only when CMake found them.
#include "siconos_peers.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include <siconos/numerics/FrictionContactProblem.h>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/LCP_Solvers.h>
#include <siconos/numerics/LinearComplementarityProblem.h>
#include <siconos/numerics/NonSmoothDrivers.h>
#include <siconos/numerics/NumericsMatrix.h>
#include <siconos/numerics/SolverOptions.h>
#include <siconos/numerics/lcp_cst.h>
#include <SiconosKernel.hpp>

#ifndef FREMOND_SICONOS_VERSION
#define FREMOND_SICONOS_VERSION "unknown"
#endif

namespace fremond::bench::siconos {

namespace {

int lcp_id(LcpSolver s) {
  switch (s) {
    case LcpSolver::lemke:
      return SICONOS_LCP_LEMKE;
    case LcpSolver::enumeration:
      return SICONOS_LCP_ENUM;
    case LcpSolver::pgs:
      return SICONOS_LCP_PGS;
    case LcpSolver::newton_fb:
      return SICONOS_LCP_NEWTON_FB_FBLSA;
  }
  throw std::invalid_argument("unknown LcpSolver");
}

int fc2d_id(Fc2dSolver s) {
  switch (s) {
    case Fc2dSolver::nsgs:
      return SICONOS_FRICTION_2D_NSGS;
    case Fc2dSolver::lemke:
      return SICONOS_FRICTION_2D_LEMKE;
    case Fc2dSolver::enumeration:
      return SICONOS_FRICTION_2D_ENUM;
    case Fc2dSolver::cpg:
      return SICONOS_FRICTION_2D_CPG;
  }
  throw std::invalid_argument("unknown Fc2dSolver");
}

void set_tolerance(SolverOptions* options, double tolerance, int max_iterations) {
  options->dparam[SICONOS_DPARAM_TOL] = tolerance;
  options->iparam[SICONOS_IPARAM_MAX_ITER] = max_iterations;
}

SolveInfo info_of(int info, const SolverOptions* options) {
  return {info, options->iparam[SICONOS_IPARAM_ITER_DONE], options->dparam[SICONOS_DPARAM_RESIDU]};
}

}  // namespace

const char* to_string(LcpSolver s) {
  switch (s) {
    case LcpSolver::lemke:
      return "lemke";
    case LcpSolver::enumeration:
      return "enumeration";
    case LcpSolver::pgs:
      return "pgs";
    case LcpSolver::newton_fb:
      return "newton_fb";
  }
  return "unknown";
}

const char* to_string(Fc2dSolver s) {
  switch (s) {
    case Fc2dSolver::nsgs:
      return "nsgs";
    case Fc2dSolver::lemke:
      return "lemke";
    case Fc2dSolver::enumeration:
      return "enumeration";
    case Fc2dSolver::cpg:
      return "cpg";
  }
  return "unknown";
}

std::string version() {
  return FREMOND_SICONOS_VERSION;
}

// --------------------------------------------------------------------------------------------
// LCP

struct Lcp::Impl {
  int n = 0;
  NumericsMatrix* M = nullptr;
  std::vector<double> q;
  LinearComplementarityProblem problem{};
  SolverOptions* options = nullptr;
};

Lcp::Lcp(int n, LcpSolver solver, double tolerance, int max_iterations)
    : impl_(std::make_unique<Impl>()) {
  impl_->n = n;
  impl_->M = NM_create(NM_DENSE, n, n);
  impl_->q.assign(n, 0.0);
  impl_->problem.size = n;
  impl_->problem.M = impl_->M;
  impl_->problem.q = impl_->q.data();
  impl_->options = solver_options_create(lcp_id(solver));
  set_tolerance(impl_->options, tolerance, max_iterations);
}

Lcp::~Lcp() {
  solver_options_delete(impl_->options);
  NM_free(impl_->M);
}

SolveInfo Lcp::solve(const double* M, const double* q, double* z, double* w) {
  const int n = impl_->n;
  std::memcpy(impl_->M->matrix0, M, sizeof(double) * n * n);
  std::memcpy(impl_->q.data(), q, sizeof(double) * n);
  std::fill(z, z + n, 0.0);
  std::fill(w, w + n, 0.0);
  const int info = linearComplementarity_driver(&impl_->problem, z, w, impl_->options);
  return info_of(info, impl_->options);
}

// --------------------------------------------------------------------------------------------
// 2-D friction contact

struct FrictionContact2d::Impl {
  int contacts = 0;
  NumericsMatrix* M = nullptr;
  std::vector<double> q, mu;
  FrictionContactProblem problem{};
  SolverOptions* options = nullptr;
};

FrictionContact2d::FrictionContact2d(int contacts, Fc2dSolver solver, double tolerance,
                                     int max_iterations)
    : impl_(std::make_unique<Impl>()) {
  const int n = 2 * contacts;
  impl_->contacts = contacts;
  impl_->M = NM_create(NM_DENSE, n, n);
  impl_->q.assign(n, 0.0);
  impl_->mu.assign(contacts, 0.0);
  impl_->problem.dimension = 2;
  impl_->problem.numberOfContacts = contacts;
  impl_->problem.M = impl_->M;
  impl_->problem.q = impl_->q.data();
  impl_->problem.mu = impl_->mu.data();
  impl_->options = solver_options_create(fc2d_id(solver));
  set_tolerance(impl_->options, tolerance, max_iterations);
}

FrictionContact2d::~FrictionContact2d() {
  solver_options_delete(impl_->options);
  NM_free(impl_->M);
}

SolveInfo FrictionContact2d::solve(const double* M, const double* q, const double* mu, double* r,
                                   double* u) {
  const int c = impl_->contacts, n = 2 * c;
  std::memcpy(impl_->M->matrix0, M, sizeof(double) * n * n);
  std::memcpy(impl_->q.data(), q, sizeof(double) * n);
  std::memcpy(impl_->mu.data(), mu, sizeof(double) * c);
  std::fill(r, r + n, 0.0);
  std::fill(u, u + n, 0.0);
  const int info = fc2d_driver(&impl_->problem, r, u, impl_->options);
  return info_of(info, impl_->options);
}

struct Fc2dFile::Impl {
  FrictionContactProblem* problem = nullptr;
  NumericsMatrix* dense = nullptr;
  NumericsMatrix* original = nullptr;
  SolverOptions* options = nullptr;
};

Fc2dFile::Fc2dFile(const std::string& path, Fc2dSolver solver, double tolerance, int max_iterations)
    : impl_(std::make_unique<Impl>()) {
  impl_->problem = frictionContact_new_from_filename(path.c_str());
  if (!impl_->problem) throw std::runtime_error("Siconos cannot read " + path);
  const int n = 2 * impl_->problem->numberOfContacts;
  impl_->dense = NM_create(NM_DENSE, n, n);
  NM_to_dense(impl_->problem->M, impl_->dense);
  impl_->original = impl_->problem->M;
  impl_->problem->M = impl_->dense;
  impl_->options = solver_options_create(fc2d_id(solver));
  set_tolerance(impl_->options, tolerance, max_iterations);
}

Fc2dFile::~Fc2dFile() {
  solver_options_delete(impl_->options);
  impl_->problem->M = impl_->original;
  NM_free(impl_->dense);
  frictionContactProblem_free(impl_->problem);
}

int Fc2dFile::contacts() const {
  return impl_->problem->numberOfContacts;
}

SolveInfo Fc2dFile::solve(std::vector<double>& r, std::vector<double>& u) {
  const std::size_t n = 2 * static_cast<std::size_t>(contacts());
  r.assign(n, 0.0);
  u.assign(n, 0.0);
  const int info = fc2d_driver(impl_->problem, r.data(), u.data(), impl_->options);
  return info_of(info, impl_->options);
}

// --------------------------------------------------------------------------------------------
// Moreau-Jean on the bar

namespace {

/// One end s = ±1 of the bar, at (x + s l cos θ, y + s l sin θ) (the paper's Fig. 1): the gap is
/// its height, h = y + s l sin θ, and the Jacobian's rows are W_Nᵀ = (0, 1, s l cos θ), W_Tᵀ = (1,
/// 0, −s l sin θ).
class BarEnd : public LagrangianScleronomousR {
 public:
  BarEnd(double s, double l) : s_(s), l_(l) { _jachq.reset(new SimpleMatrix(2, 3)); }
  void computeh(const BlockVector& q, BlockVector&, SiconosVector& y) override {
    y.setValue(0, q.getValue(1) + s_ * l_ * std::sin(q.getValue(2)));
    y.setValue(1, 0.0);
  }
  void computeJachq(const BlockVector& q, BlockVector&) override {
    const double th = q.getValue(2);
    _jachq->setValue(0, 0, 0.0);
    _jachq->setValue(0, 1, 1.0);
    _jachq->setValue(0, 2, s_ * l_ * std::cos(th));
    _jachq->setValue(1, 0, 1.0);
    _jachq->setValue(1, 1, 0.0);
    _jachq->setValue(1, 2, -s_ * l_ * std::sin(th));
  }

 private:
  double s_, l_;
};

}  // namespace

MoreauJeanRun simulate_bar_moreau_jean(const MoreauJeanSettings& st) {
  // the paper's Fig. 1.
  constexpr double m = 1.0, l = 0.5, J = m * l * l / 3.0, g = 9.81;
  auto q0 = std::make_shared<SiconosVector>(3);
  auto v0 = std::make_shared<SiconosVector>(3);
  (*q0)(0) = 0.0;
  (*q0)(1) = 1.0;
  (*q0)(2) = M_PI / 4.0;
  (*v0)(0) = 2.0;
  auto mass = std::make_shared<SimpleMatrix>(3, 3);
  (*mass)(0, 0) = m;
  (*mass)(1, 1) = m;
  (*mass)(2, 2) = J;
  auto bar = std::make_shared<LagrangianLinearTIDS>(q0, v0, mass);
  auto weight = std::make_shared<SiconosVector>(3);
  (*weight)(1) = -m * g;
  bar->setFExtPtr(weight);

  auto nsds = std::make_shared<NonSmoothDynamicalSystem>(0.0, st.duration);
  nsds->insertDynamicalSystem(bar);
  auto law = std::make_shared<NewtonImpactFrictionNSL>(st.e, 0.0, st.mu, 2);
  const double sides[2] = {1.0, -1.0};
  SP::Interaction ends[2];
  for (int i = 0; i < 2; ++i) {
    ends[i] = std::make_shared<Interaction>(law, std::make_shared<BarEnd>(sides[i], l));
    nsds->link(ends[i], bar);
  }
  auto osi = std::make_shared<MoreauJeanOSI>(st.theta);
  auto td = std::make_shared<TimeDiscretisation>(0.0, st.h);
  auto osnspb = std::make_shared<FrictionContact>(2, fc2d_id(st.solver));
  osnspb->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = st.tolerance;
  auto sim = std::make_shared<TimeStepping>(nsds, td, osi, osnspb);

  const SP::SiconosVector q = bar->q();
  const SP::SiconosVector v = bar->velocity();
  auto energy = [&] {
    return 0.5 * (m * (*v)(0) * (*v)(0) + m * (*v)(1) * (*v)(1) + J * (*v)(2) * (*v)(2)) +
           m * g * (*q)(1);
  };

  MoreauJeanRun run;
  run.energy_initial = energy();
  double previous_energy = run.energy_initial;
  bool in_contact[2] = {false, false};
  const auto start = std::chrono::steady_clock::now();
  timespec cpu_start{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_start);
  while (sim->hasNextEvent()) {
    sim->computeOneStep();
    const double t = sim->nextTime();
    for (int i = 0; i < 2; ++i) {
      const double height = (*q)(1) + sides[i] * l * std::sin((*q)(2));
      run.max_penetration = std::max(run.max_penetration, -height);
      const SP::SiconosVector lambda = ends[i]->lambda(1);
      const bool active = lambda && (*lambda)(0) > 0.0;
      if (active && !in_contact[i]) {
        run.impact_times.push_back(t);
        run.impact_ends.push_back(static_cast<int>(sides[i]));
        if (run.qdot_after_first_impact.empty())
          run.qdot_after_first_impact = {(*v)(0), (*v)(1), (*v)(2)};
      }
      in_contact[i] = active;
    }
    const double e_now = energy();
    run.energy_max_increase = std::max(run.energy_max_increase, e_now - previous_energy);
    previous_energy = e_now;
    sim->nextStep();
    ++run.steps;
  }
  timespec cpu_end{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu_end);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu_seconds = static_cast<double>(cpu_end.tv_sec - cpu_start.tv_sec) +
                    1e-9 * static_cast<double>(cpu_end.tv_nsec - cpu_start.tv_nsec);
  run.microseconds_per_step = 1e6 * run.cpu_seconds / std::max(run.steps, 1);
  run.q_final = {(*q)(0), (*q)(1), (*q)(2)};
  run.qdot_final = {(*v)(0), (*v)(1), (*v)(2)};
  run.energy_final = energy();
  return run;
}

}  // namespace fremond::bench::siconos
