// solve_batch: each result is solve_impact's to the last bit, whatever the number of threads; the
// momentum balance M (q̇_E − q̇_A) = W_N P_N + W_T P_T holds for every answer; an invalid problem
// is named by its index and nothing is returned.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond {
namespace {

// Bars at random angles and velocities, every one approaching at its lower end.
std::vector<ImpactProblem> bars(int count, bool both_ends) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> angle(0.05, 1.5), speed(-3.0, 3.0);
  std::vector<ImpactProblem> out;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d qdot(speed(rng), -1.0 - std::fabs(speed(rng)), speed(rng));
    out.push_back(fixtures::bar(angle(rng), qdot, both_ends));
  }
  return out;
}

void expect_identical(const ImpactResult& a, const ImpactResult& b, int i) {
  SCOPED_TRACE("problem " + std::to_string(i));
  EXPECT_EQ(a.solver.status, b.solver.status);
  EXPECT_EQ(a.solver.residual, b.solver.residual);
  EXPECT_EQ(a.solver.attempt_count, b.solver.attempt_count);
  EXPECT_EQ(a.qdot_E, b.qdot_E);
  EXPECT_EQ(a.P_N, b.P_N);
  EXPECT_EQ(a.P_T, b.P_T);
  EXPECT_EQ(a.energy_change, b.energy_change);
  EXPECT_EQ(a.admissibility.admissible, b.admissibility.admissible);
}

TEST(SolveBatch, EachResultIsSolveImpactsToTheLastBitOnOneOrTwoThreads) {
  const PowerPotential phi(4.0, 3.0);
  for (const ImpactLaw& law : {ImpactLaw::newton_coulomb(0.9, 1.0), ImpactLaw::poisson(0.5),
                               ImpactLaw::fremond_coulomb(phi, 0.3)}) {
    SCOPED_TRACE(law.describe());
    const std::vector<ImpactProblem> problems = bars(300, true);
    std::vector<ImpactResult> one_by_one;
    for (const auto& p : problems) one_by_one.push_back(solve_impact(p, law));
    for (int threads : {1, 2, 5}) {
      const std::vector<ImpactResult> batch = solve_batch(problems, law, {}, {threads});
      ASSERT_EQ(batch.size(), problems.size());
      for (std::size_t i = 0; i < problems.size(); ++i)
        expect_identical(batch[i], one_by_one[i], static_cast<int>(i));
    }
  }
}

// A batch long enough (milliseconds) that the other workers start beside the calling thread and
// share its blocks: every answer is still the one-thread batch's, and the first invalid problem
// by index is named, though a later one may be met first by another worker.
TEST(SolveBatch, ALongBatchSharedAmongWorkersGivesTheSameAnswersAndErrors) {
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  std::vector<SmallImpactProblem> problems;
  for (const ImpactProblem& p : bars(6000, false)) problems.push_back(to_small(p));
  const std::vector<SmallImpactResult> one = solve_batch(problems, law, {}, {1});
  for (int threads : {2, 5}) {
    const std::vector<SmallImpactResult> shared = solve_batch(problems, law, {}, {threads});
    ASSERT_EQ(shared.size(), one.size());
    for (std::size_t i = 0; i < one.size(); ++i)
      expect_identical(to_dynamic(shared[i]), to_dynamic(one[i]), static_cast<int>(i));
  }
  problems[5900].M(0, 0) = NAN;
  problems[4100].M(2, 2) = -1.0;  // the first by index
  for (int threads : {1, 2}) {
    try {
      (void)solve_batch(problems, law, {}, {threads});
      FAIL() << "an invalid problem was solved";
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), "problems[4100].M") << e.what();
    }
  }
}

TEST(SolveBatch, SmallProblemsGiveTheSameAnswersWithoutHeapResults) {
  const ImpactLaw law = ImpactLaw::newton_coulomb(0.9, 1.0);
  const std::vector<ImpactProblem> problems = bars(200, true);
  std::vector<SmallImpactProblem> small;
  for (const auto& p : problems) small.push_back(to_small(p));
  const std::vector<ImpactResult> heap = solve_batch(problems, law, {}, {2});
  const std::vector<SmallImpactResult> stack = solve_batch(small, law, {}, {2});
  ASSERT_EQ(stack.size(), heap.size());
  for (std::size_t i = 0; i < heap.size(); ++i)
    expect_identical(to_dynamic(stack[i]), heap[i], static_cast<int>(i));
}

TEST(SolveBatch, IntoTheCallersResultsWhichMustFit) {
  const ImpactLaw law = ImpactLaw::poisson_coulomb(0.5, 0.4);
  const std::vector<ImpactProblem> problems = bars(100, true);
  std::vector<ImpactResult> results(problems.size());
  std::vector<SmallImpactResult> small(problems.size());
  std::vector<SmallImpactProblem> small_problems;
  for (const auto& p : problems) small_problems.push_back(to_small(p));
  // Each batch overwrites the last one's answers, under another law: nothing of Poisson's phases
  // or Frémond's reaction stays behind.
  for (const ImpactLaw& l : {law, ImpactLaw::fremond_coulomb(PowerPotential(4.0, 3.0), 0.3), law,
                             ImpactLaw::newton(0.8)}) {
    SCOPED_TRACE(l.describe());
    solve_batch(std::span<const ImpactProblem>(problems), l, std::span(results), {}, {2});
    solve_batch(std::span<const SmallImpactProblem>(small_problems), l, std::span(small), {}, {2});
    for (std::size_t i = 0; i < problems.size(); ++i) {
      const ImpactResult alone = solve_impact(problems[i], l);
      for (const ImpactResult& r : {results[i], to_dynamic(small[i])}) {
        expect_identical(r, alone, static_cast<int>(i));
        EXPECT_EQ(r.has_phases, alone.has_phases);
        EXPECT_EQ(r.P_NC, alone.P_NC);
        EXPECT_EQ(r.qdot_C, alone.qdot_C);
        EXPECT_EQ(r.P_N_reaction, alone.P_N_reaction);
        EXPECT_EQ(r.admissibility.reaction, alone.admissibility.reaction);
      }
    }
  }
  std::vector<ImpactResult> short_list(problems.size() - 1);
  try {
    solve_batch(std::span<const ImpactProblem>(problems), law, std::span(short_list));
    FAIL() << "99 results were accepted for 100 problems";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "results") << e.what();
  }
}

TEST(SolveBatch, EveryAnswerBalancesMomentum) {
  const std::vector<ImpactProblem> problems = bars(500, false);
  const std::vector<ImpactResult> batch =
      solve_batch(problems, ImpactLaw::newton_coulomb(0.9, 1.0));
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const ImpactProblem& p = problems[i];
    const ImpactResult& r = batch[i];
    ASSERT_EQ(r.solver.status, SolverStatus::converged) << i;
    const Eigen::Vector3d lhs = p.M * (r.qdot_E - p.qdot_A);
    const Eigen::Vector3d rhs = p.W_N * r.P_N + p.W_T * r.P_T;
    EXPECT_LE((lhs - rhs).cwiseAbs().maxCoeff(), 1e-13 * (1.0 + rhs.cwiseAbs().maxCoeff())) << i;
    EXPECT_GE(r.D_NE(0), -1e-12) << i;  // no penetration after the impact
  }
}

TEST(SolveBatch, TheFirstInvalidProblemIsNamedByItsIndex) {
  std::vector<ImpactProblem> problems = bars(400, false);
  problems[7].M(2, 2) = -1.0;   // not positive definite
  problems[300].M(0, 0) = NAN;  // a later one, not the first
  try {
    (void)solve_batch(problems, ImpactLaw::newton(0.5), {}, {2});
    FAIL() << "an invalid problem was solved";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "problems[7].M") << e.what();
  }
}

TEST(SolveBatch, ALawThatDoesNotFitAProblemNamesBoth) {
  std::vector<ImpactProblem> problems = bars(3, false);
  problems.push_back(bars(1, true).front());  // two contacts: the law fits this one only
  try {
    (void)solve_batch(problems, ImpactLaw::newton(PerContact{0.5, 0.6}), {}, {1});
    FAIL() << "a law of two contacts was applied to one";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "law.e") << e.what();
    EXPECT_NE(std::string(e.what()).find("problems[0]"), std::string::npos) << e.what();
  }
}

// One bar at a fixed angle and 300 velocities before the impact, its lower end approaching or
// leaving, the upper one too (two contacts).
Eigen::MatrixXd velocities(int count) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> speed(-3.0, 3.0);
  Eigen::MatrixXd v(3, count);
  for (int i = 0; i < count; ++i) v.col(i) << speed(rng), speed(rng), speed(rng);
  return v;
}

// The bar on one contact (the laws' one-contact lanes, whose columns skip the whole result) and
// on two; its velocities approach or separate.
TEST(SolveBatch, OneConfigurationManyVelocitiesGivesSolveImpactsAnswers) {
  const Eigen::MatrixXd v = velocities(300);
  for (const bool both_ends : {false, true})
    for (const ImpactLaw& law : {ImpactLaw::newton_coulomb(0.9, 1.0), ImpactLaw::poisson(0.5),
                                 ImpactLaw::poisson_coulomb(0.5, 0.3),
                                 ImpactLaw::fremond_coulomb(PowerPotential(4.0, 3.0), 0.3)}) {
      SCOPED_TRACE(law.describe() + (both_ends ? ", both ends" : ", one end"));
      const ImpactProblem bar = fixtures::bar(0.7, Eigen::Vector3d(0.0, -1.0, 0.0), both_ends);
      std::vector<ImpactResult> alone;
      for (int i = 0; i < v.cols(); ++i) {
        ImpactProblem p = bar;
        p.qdot_A = v.col(i);
        alone.push_back(solve_impact(p, law));
      }
      const ImpactSolver heap(bar, law);
      const SmallImpactSolver small(to_small(bar), law);
      for (int threads : {1, 2, 5}) {
        const std::vector<ImpactResult> a = solve_batch(heap, v, {threads});
        const std::vector<SmallImpactResult> b = solve_batch(small, v, {threads});
        BatchAnswers columns, heap_columns;
        solve_batch(small, v, columns, {threads});
        solve_batch(heap, v, heap_columns, {threads});
        ASSERT_EQ(a.size(), alone.size());
        ASSERT_EQ(b.size(), alone.size());
        for (const BatchAnswers* c : {&columns, &heap_columns}) {
          ASSERT_EQ(c->size(), v.cols());
          for (std::size_t i = 0; i < alone.size(); ++i) {
            const ImpactResult& r = alone[i];
            const auto k = static_cast<Eigen::Index>(i);
            EXPECT_TRUE(c->qdot_E.col(k) == r.qdot_E && c->P_N.col(k) == r.P_N &&
                        c->P_T.col(k) == r.P_T && c->D_NE.col(k) == r.D_NE &&
                        c->D_TE.col(k) == r.D_TE)
                << "impact " << i;
            EXPECT_EQ(c->energy_change(k), r.energy_change) << i;
            EXPECT_EQ(c->residual(k), r.solver.residual) << i;
            EXPECT_EQ(c->status[i], r.solver.status) << i;
            EXPECT_EQ(c->admissible[i], r.admissibility.admissible ? 1 : 0) << i;
            EXPECT_EQ(c->unique[i], r.unique ? 1 : 0) << i;
          }
        }
        for (std::size_t i = 0; i < alone.size(); ++i) {
          const ImpactResult& r = alone[i];
          expect_identical(a[i], r, static_cast<int>(i));
          expect_identical(to_dynamic(b[i]), r, static_cast<int>(i));
          EXPECT_EQ(a[i].D_NE, r.D_NE);
          EXPECT_EQ(a[i].admissibility.total, r.admissibility.total);
        }
      }
      // The solver given is left as it was: nothing solved on it.
      EXPECT_EQ(heap.result().solver.status, SolverStatus::not_run);
    }
}

// A solve into a column of the caller's answers: the column is the solve's answer, the solver's
// own result stays as the last solve() left it, and answers of other sizes or a column outside
// them are refused, named, before anything is solved.
TEST(SolveBatch, ASolveIntoAColumnLeavesTheSolversResultAndNamesBadColumns) {
  const ImpactProblem bar = fixtures::bar(0.7, Eigen::Vector3d(0.3, -1.0, 0.2));
  SmallImpactSolver solver(to_small(bar), ImpactLaw::newton_coulomb(0.9, 1.0));
  const Eigen::Vector3d first(0.3, -1.0, 0.2), second(-0.4, -2.0, 1.0);
  const SmallImpactResult kept = solver.solve(first);
  BatchAnswers answers;
  answers.resize(3, 1, 4);
  solver.solve_into(second, answers, 2);
  ImpactProblem at_second = bar;
  at_second.qdot_A = second;
  const ImpactResult r = solve_impact(at_second, ImpactLaw::newton_coulomb(0.9, 1.0));
  EXPECT_TRUE(answers.qdot_E.col(2) == r.qdot_E);
  EXPECT_EQ(answers.P_N(0, 2), r.P_N(0));
  EXPECT_EQ(answers.residual(2), r.solver.residual);
  EXPECT_EQ(answers.admissible[2], r.admissibility.admissible ? 1 : 0);
  EXPECT_TRUE(solver.result().qdot_E == kept.qdot_E);
  EXPECT_TRUE(Eigen::VectorXd(solver.problem().qdot_A) == Eigen::VectorXd(second));
  auto name_of = [&](BatchAnswers& a, Eigen::Index column) {
    try {
      solver.solve_into(first, a, column);
    } catch (const InvalidArgument& e) {
      return e.name();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(name_of(answers, 4), "column");
  EXPECT_EQ(name_of(answers, -1), "column");
  BatchAnswers other;
  other.resize(3, 2, 4);
  EXPECT_EQ(name_of(other, 0), "answers");
  EXPECT_TRUE(Eigen::VectorXd(solver.problem().qdot_A) == Eigen::VectorXd(second));
  EXPECT_EQ(name_of(answers, 3), "accepted");
}

// A method the law does not solve (Stronge's law has no Lemke) answers `unsupported` with no
// velocities or percussions: their columns are NaN, not whatever the memory held.
TEST(SolveBatch, ColumnsOfAnUnsupportedMethodAreNaN) {
  const ImpactProblem bar = fixtures::bar(0.7, Eigen::Vector3d(0.0, -1.0, 0.0), true);
  SolverOptions lemke;
  lemke.method = SolverMethod::lemke;
  const SmallImpactSolver solver(to_small(bar), StrongeLaw{0.8, true, 0.5}, lemke);
  BatchAnswers columns;
  solve_batch(solver, velocities(50), columns, {2});
  ASSERT_EQ(columns.size(), 50);
  for (std::size_t i = 0; i < 50; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    EXPECT_EQ(columns.status[i], SolverStatus::unsupported) << i;
    EXPECT_TRUE(columns.qdot_E.col(k).array().isNaN().all()) << i;
    EXPECT_TRUE(columns.P_N.col(k).array().isNaN().all()) << i;
  }
}

TEST(SolveBatch, OneConfigurationNamesTheFirstBadVelocity) {
  const ImpactProblem bar = fixtures::bar(0.7, Eigen::Vector3d(0.0, -1.0, 0.0), true);
  const ImpactSolver solver(bar, ImpactLaw::newton_coulomb(0.9, 1.0));
  Eigen::MatrixXd v = velocities(400);
  v(1, 7) = NAN;
  v(0, 300) = INFINITY;
  auto name_of = [&](const Eigen::MatrixXd& velocities, std::size_t results) {
    std::vector<ImpactResult> out(results);
    try {
      solve_batch(solver, velocities, std::span(out), {2});
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(name_of(v, 400).rfind("qdot_A[7][1]: must be a finite number", 0), 0)
      << name_of(v, 400);
  EXPECT_EQ(name_of(v.topRows(2), 400).rfind("qdot_A: must have 3 rows", 0), 0)
      << name_of(v.topRows(2), 400);
  EXPECT_EQ(name_of(v.rightCols(10), 9).rfind("results: needs one entry per velocity (10)", 0), 0)
      << name_of(v.rightCols(10), 9);
  EXPECT_EQ(name_of(v.rightCols(10), 10), "accepted");
  BatchAnswers columns;
  try {
    solve_batch(solver, v, columns, {2});
    FAIL() << "a velocity that is not a number was solved";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "qdot_A[7][1]") << e.what();
  }
}

TEST(SolveBatch, RefusesANegativeThreadCountAndAcceptsNoProblems) {
  EXPECT_THROW((void)solve_batch(bars(2, false), ImpactLaw::newton(0.5), {}, {-1}),
               InvalidArgument);
  EXPECT_TRUE(solve_batch(std::vector<ImpactProblem>{}, ImpactLaw::newton(0.5)).empty());
}

}  // namespace
}  // namespace fremond
