// No heap allocation inside a solve of a stack-stored problem (SmallImpactProblem): every Frémond
// method except NLopt, and the classical laws, on the shared problems (tests/support/fixtures.hpp).
//
// The test replaces the global operator new and the C allocation functions of this executable (the
// library's calls resolve to them too) by counting wrappers around glibc's allocator; counting is
// on only around solve_impact, in this thread. A failure names the case and prints the call stack
// of the first allocation. Skipped under AddressSanitizer, which owns the allocator.
#include <execinfo.h>
#include <gtest/gtest.h>

#include <cerrno>
#include <cstdlib>
#include <new>
#include <sstream>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define FREMOND_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FREMOND_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef FREMOND_COUNT_ALLOCATIONS
#define FREMOND_COUNT_ALLOCATIONS 1
#endif

namespace {

thread_local bool t_counting = false;
thread_local long t_count = 0;
thread_local int t_frames = 0;
thread_local void* t_stack[24];

#if FREMOND_COUNT_ALLOCATIONS  // the counting wrappers below are its only callers
thread_local bool t_in_hook = false;

void note_allocation() {
  if (!t_counting || t_in_hook) return;
  t_in_hook = true;
  if (t_count++ == 0) t_frames = backtrace(t_stack, 24);
  t_in_hook = false;
}
#endif

}  // namespace

#if FREMOND_COUNT_ALLOCATIONS
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);

void* malloc(std::size_t n) {
  note_allocation();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t s) {
  note_allocation();
  return __libc_calloc(n, s);
}
void* realloc(void* p, std::size_t n) {
  note_allocation();
  return __libc_realloc(p, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) {
  note_allocation();
  return __libc_memalign(a, n);
}
int posix_memalign(void** out, std::size_t a, std::size_t n) {
  note_allocation();
  void* p = __libc_memalign(a, n);
  if (!p) return ENOMEM;
  *out = p;
  return 0;
}
}  // extern "C"

namespace {
// Out of line, so that the compiler does not pair an inlined operator new with free().
[[gnu::noinline]] void release(void* p) noexcept {
  __libc_free(p);
}
}  // namespace

void* operator new(std::size_t n) {
  note_allocation();
  if (void* p = __libc_malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  return ::operator new(n);
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  note_allocation();
  return __libc_malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return ::operator new(n, std::nothrow);
}
void* operator new(std::size_t n, std::align_val_t a) {
  note_allocation();
  if (void* p = __libc_memalign(static_cast<std::size_t>(a), n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) {
  return ::operator new(n, a);
}
void operator delete(void* p) noexcept {
  release(p);
}
void operator delete[](void* p) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  release(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  release(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  release(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  release(p);
}
#endif  // FREMOND_COUNT_ALLOCATIONS

namespace fremond {
namespace {

using namespace fremond::fixtures;

/// Allocations during f(), with the call stack of the first one.
template <class F>
long allocations(F&& f, std::string* where) {
  f();  // a first call may set up lazily (e.g. the dynamic loader resolving symbols)
  t_count = 0;
  t_frames = 0;
  t_counting = true;
  f();
  t_counting = false;
  const long n = t_count;
  if (n > 0 && where) {
    char** names = backtrace_symbols(t_stack, t_frames);
    std::ostringstream os;
    for (int i = 0; i < t_frames; ++i) os << "    " << (names ? names[i] : "?") << "\n";
    std::free(names);
    *where = os.str();
  }
  return n;
}

void require_counting() {
#if !FREMOND_COUNT_ALLOCATIONS
  GTEST_SKIP() << "built with AddressSanitizer: allocations are not counted";
#endif
}

// The counter sees allocations made inside the library: a dynamic-size solve allocates.
TEST(NoAllocation, TheCounterSeesTheLibrarysAllocations) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  const ImpactProblem p = to_dynamic(bar_first_impact(true));
  const ImpactLaw law = ImpactLaw::newton(0.9);
  std::string where;
  ImpactResult r;
  EXPECT_GT(allocations([&] { r = solve_impact(p, law); }, &where), 0);
  // Eigen's heap storage goes through malloc, not operator new: counted too.
  const SmallImpactProblem small = bar_first_impact(true);
  ImpactProblem d;
  EXPECT_GE(allocations([&] { d = to_dynamic(small); }, &where), 4);
}

struct Case {
  std::string name;
  SmallImpactProblem problem;
  ImpactLaw law;
};

std::vector<Case> fremond_cases() {
  const auto [p3, viscous, coulomb] = bar_fremond_laws();
  std::vector<Case> v;
  v.push_back({"bar p3", bar_first_impact(false), p3});
  v.push_back({"bar p3 viscous", bar_first_impact(true), viscous});
  v.push_back({"bar p3 coulomb", bar_first_impact(true), coulomb});
  for (double p : {1.1, 2.0, 3.0, 10.0})
    v.push_back({"point mass p" + std::to_string(p), planar_point_mass(1.0, false),
                 ImpactLaw::fremond(PowerPotential(4.0, p))});
  v.push_back({"flat bar p3", flat_bar_two_contacts(false), p3});
  v.push_back({"flat bar p3 viscous", flat_bar_two_contacts(true), viscous});
  v.push_back({"flat bar p3 coulomb", flat_bar_two_contacts(true), coulomb});
  // More than twice as many rows as dofs: Newton in velocity space first.
  v.push_back({"plate c4 viscous", to_small(plate_many_contacts(4, true)), viscous});
  v.push_back({"two point masses p3", two_point_masses(false), p3});
  v.push_back({"two point masses viscous", two_point_masses(true), viscous});
  v.push_back({"two point masses coulomb", two_point_masses(true), coulomb});
  for (int i = 0; i < 4; ++i) {
    v.push_back({"random " + std::to_string(i) + " p3", random_spd_problem(i, false), p3});
    v.push_back({"random " + std::to_string(i) + " viscous", random_spd_problem(i, true), viscous});
    v.push_back({"random " + std::to_string(i) + " coulomb", random_spd_problem(i, true), coulomb});
  }
  return v;
}

TEST(NoAllocation, FremondSmallProblemEveryMethodButNlopt) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  for (const Case& c : fremond_cases()) {
    for (SolverMethod m : {SolverMethod::automatic, SolverMethod::closed_form,
                           SolverMethod::scalar_newton, SolverMethod::mode_enumeration,
                           SolverMethod::semismooth_newton, SolverMethod::proximal}) {
      SolverOptions opt;
      opt.method = m;
      SmallImpactResult r;
      std::string where;
      const long n = allocations([&] { r = solve_impact(c.problem, c.law, opt); }, &where);
      if (r.solver.status == SolverStatus::unsupported) continue;
      if (r.solver.method == SolverMethod::nlopt) continue;  // automatic fell back to NLopt
      EXPECT_EQ(n, 0) << c.name << ", method " << to_string(m) << " (answered by "
                      << to_string(r.solver.method) << ", " << to_string(r.solver.status)
                      << "): first allocation at\n"
                      << where;
    }
  }
}

TEST(NoAllocation, ClassicalLawsSmallProblem) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  const std::vector<std::pair<std::string, ImpactLaw>> laws{
      {"newton", ImpactLaw::newton(0.9)},
      {"poisson", ImpactLaw::poisson(0.9)},
      {"newton_coulomb", ImpactLaw::newton_coulomb(0.9, 1.0)},
      {"poisson_coulomb", ImpactLaw::poisson_coulomb(0.9, 1.0)}};
  std::vector<std::pair<std::string, SmallImpactProblem>> problems{
      {"bar", bar_first_impact(true)},
      {"point mass", planar_point_mass(1.0, true)},
      {"flat bar", flat_bar_two_contacts(true)},
      {"two point masses", two_point_masses(true)}};
  for (int i = 0; i < 4; ++i)
    problems.push_back({"random " + std::to_string(i), random_spd_problem(i, true)});
  for (const auto& [pname, p] : problems)
    for (const auto& [lname, law] : laws)
      for (const bool unique : {false, true}) {
        SolverOptions opt;
        opt.check_uniqueness = unique;
        SmallImpactResult r;
        std::string where;
        const long n =
            allocations([&, &p = p, &law = law] { r = solve_impact(p, law, opt); }, &where);
        EXPECT_EQ(n, 0) << lname << " on " << pname << ", check_uniqueness " << unique << " ("
                        << to_string(r.solver.method) << ", " << to_string(r.solver.status)
                        << "): first allocation at\n"
                        << where;
      }
}

// The velocity-space solve of a classical mode (classical_velocity_mode.hpp) runs only where an
// answer is still beyond rounding: two contacts closing on a two-dof body with cond(M) = 2e9.
TEST(NoAllocation, ClassicalModeSolvedForItsVelocities) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  SmallImpactProblem p;
  p.M = SmallImpactProblem::Mat(2, 2);
  p.M << 20020865.219324283, 12189185.166647436, 12189185.166647436, 7421069.6412495691;
  p.W_N = SmallImpactProblem::Jac(2, 2);
  p.W_N << -0.82138343776774914, 0.67160663654018937, 0.71750379326275238, -0.15782769523263629;
  p.W_T = SmallImpactProblem::Jac(2, 2);
  p.W_T << -0.03729301742693325, -0.30188112988670768, -0.82600760964509301, 0.2954026963744385;
  p.qdot_A = SmallImpactProblem::Vec(2);
  p.qdot_A << -4.5863067036418446e-12, -8.0835310028874393e-12;
  const std::vector<double> e{0.20025873288569646, 0.21829989042951392};
  for (const ImpactLaw& law : {ImpactLaw::newton(e), ImpactLaw::newton_coulomb(e, {0.3, 0.3})}) {
    SmallImpactResult r;
    std::string where;
    const long n = allocations([&, &law = law] { r = solve_impact(p, law); }, &where);
    EXPECT_EQ(r.solver.status, SolverStatus::converged) << law.name();
    EXPECT_EQ(n, 0) << law.name() << ": first allocation at\n" << where;
  }
}

/// How many heap blocks a result holds: one per non-empty vector.
int heap_blocks(const ImpactResult& r) {
  int k = 0;
  for (const Eigen::VectorXd* v :
       {&r.qdot_E, &r.P_N, &r.P_T, &r.D_NA, &r.D_TA, &r.D_NE, &r.D_TE, &r.P_N_reaction, &r.P_NC,
        &r.P_TC, &r.D_NC, &r.D_TC, &r.qdot_C, &r.admissibility.per_contact})
    k += v->size() > 0 ? 1 : 0;
  return k + (r.takes_part.size() > 0 ? 1 : 0);
}

// A heap-stored problem that fits the small form is solved in it (solve_impact.hpp): the solve
// allocates the result's vectors and nothing else (in its own storage: some 70 blocks on the bar).
TEST(NoAllocation, HeapStoredSmallProblemAllocatesOnlyItsResult) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  const std::vector<std::pair<std::string, ImpactLaw>> laws{
      {"newton_coulomb", ImpactLaw::newton_coulomb(0.9, 1.0)},
      {"poisson_coulomb", ImpactLaw::poisson_coulomb(0.9, 1.0)},
      {"fremond viscous", bar_fremond_laws().viscous}};
  for (const SmallImpactProblem& small : {bar_first_impact(true), flat_bar_two_contacts(true)})
    for (const auto& [name, law] : laws) {
      const ImpactProblem p = to_dynamic(small);
      ImpactResult r;
      std::string where;
      const long n = allocations([&, &law = law] { r = solve_impact(p, law); }, &where);
      EXPECT_TRUE(r.ok()) << name;
      EXPECT_GE(heap_blocks(r), 9) << name;
      EXPECT_EQ(n, heap_blocks(r))
          << name << " on " << p.contacts() << " contacts: an allocation beside the result's at\n"
          << where;
    }
}

// The prepared solver (impact_solver.hpp) keeps its answer's storage from one solve to the next:
// a small problem, heap-stored or not, allocates nothing at all once the first answer is made.
TEST(NoAllocation, PreparedSolverAllocatesNothingPerSolve) {
  require_counting();
  if (::testing::Test::IsSkipped()) return;
  const std::vector<std::pair<std::string, ImpactLaw>> laws{
      {"newton_coulomb", ImpactLaw::newton_coulomb(0.9, 1.0)},
      {"poisson_coulomb", ImpactLaw::poisson_coulomb(0.9, 1.0)},
      {"fremond viscous", bar_fremond_laws().viscous},
      {"fremond coulomb", bar_fremond_laws().coulomb}};
  for (const SmallImpactProblem& small : {bar_first_impact(true), flat_bar_two_contacts(true)})
    for (const auto& [name, law] : laws) {
      SmallImpactSolver stack_solver(small, law);
      ImpactSolver heap_solver(to_dynamic(small), law);
      Eigen::VectorXd q = small.qdot_A;
      std::string where;
      long n = allocations([&] { stack_solver.solve(q); }, &where);
      EXPECT_EQ(n, 0) << name << ", small solver: first allocation at\n" << where;
      n = allocations([&] { heap_solver.solve(q); }, &where);
      EXPECT_TRUE(heap_solver.result().ok()) << name;
      EXPECT_EQ(n, 0) << name << ", heap-stored solver: first allocation at\n" << where;
    }
}

}  // namespace
}  // namespace fremond
