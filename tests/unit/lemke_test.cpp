// The public LCP solver (solvers/lemke.hpp) against hand solutions and a brute-force enumeration of
// complementary bases.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "fremond/core/error.hpp"
#include "fremond/solvers/lemke.hpp"

namespace fremond {
namespace {

// Every solution of LCP(M, q) found by trying each complementary basis: z_S = −M_SS⁻¹ q_S, the
// other z zero, kept when z ≥ 0 and w = Mz + q ≥ 0. Independent of Lemke's pivoting.
std::vector<VectorX> brute_force(const MatrixX& M, const VectorX& q) {
  const int n = static_cast<int>(q.size());
  std::vector<VectorX> all;
  const double tol = 1e-9 * (1.0 + q.cwiseAbs().maxCoeff());
  for (int set = 0; set < (1 << n); ++set) {
    std::vector<int> s;
    for (int i = 0; i < n; ++i)
      if (set & (1 << i)) s.push_back(i);
    const int k = static_cast<int>(s.size());
    MatrixX Ms(k, k);
    VectorX qs(k);
    for (int i = 0; i < k; ++i) {
      qs(i) = q(s[i]);
      for (int j = 0; j < k; ++j) Ms(i, j) = M(s[i], s[j]);
    }
    VectorX z = VectorX::Zero(n);
    if (k) {
      Eigen::FullPivLU<MatrixX> lu(Ms);
      if (lu.rank() < k) continue;
      const VectorX zs = lu.solve(-qs);
      for (int i = 0; i < k; ++i) z(s[i]) = zs(i);
    }
    const VectorX w = M * z + q;
    if (z.minCoeff() < -tol || w.minCoeff() < -tol) continue;
    bool seen = false;
    for (const auto& y : all) seen = seen || (y - z).cwiseAbs().maxCoeff() < 1e-7;
    if (!seen) all.push_back(z);
  }
  return all;
}

TEST(Lemke, SolvesATwoByTwoByHand) {
  // 2 z1 + z2 = 5, z1 + 2 z2 = 6 with both z > 0: z = (4/3, 7/3), w = 0.
  MatrixX M(2, 2);
  M << 2, 1, 1, 2;
  const VectorX q = Eigen::Vector2d(-5, -6);
  const LcpResult r = solve_lcp(M, q);
  ASSERT_EQ(r.status, LcpStatus::solved);
  EXPECT_NEAR(r.z(0), 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(r.z(1), 7.0 / 3.0, 1e-14);
  EXPECT_NEAR(r.w.cwiseAbs().maxCoeff(), 0.0, 1e-14);
  EXPECT_LE(r.residual, 1e-15);
}

TEST(Lemke, OneVariableOpensWhenTheOtherPushesIt) {
  // M = [[1, 2], [0, 1]], q = (−1, 1): z2 = 0 (w2 = 1 > 0), z1 = 1, w = (0, 1).
  MatrixX M(2, 2);
  M << 1, 2, 0, 1;
  const LcpResult r = solve_lcp(M, VectorX(Eigen::Vector2d(-1, 1)));
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.z(0), 1.0, 1e-15);
  EXPECT_EQ(r.z(1), 0.0);
  EXPECT_NEAR(r.w(1), 1.0, 1e-15);
}

TEST(Lemke, NonNegativeQNeedsNoPivot) {
  const MatrixX M = MatrixX::Identity(3, 3);
  const LcpResult r = solve_lcp(M, VectorX(Eigen::Vector3d(1, 0, 2)));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.pivots, 0);
  EXPECT_EQ(r.z.cwiseAbs().maxCoeff(), 0.0);
}

TEST(Lemke, PMatricesMatchTheBruteForceSolution) {
  // M with a positive definite symmetric part is a P-matrix: exactly one solution for every q.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 8;
    MatrixX A(n, n), S(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        A(i, j) = u(rng);
        S(i, j) = u(rng);
      }
    const MatrixX M = A * A.transpose() + 0.05 * MatrixX::Identity(n, n) + (S - S.transpose());
    VectorX q(n);
    for (int i = 0; i < n; ++i) q(i) = 3 * u(rng);
    const auto ref = brute_force(M, q);
    ASSERT_EQ(ref.size(), 1u) << "trial " << trial;
    const LcpResult r = solve_lcp(M, q);
    ASSERT_TRUE(r.ok()) << "trial " << trial << ": " << to_string(r.status);
    EXPECT_LE((r.z - ref[0]).cwiseAbs().maxCoeff(), 1e-10 * (1 + ref[0].cwiseAbs().maxCoeff()))
        << "trial " << trial;
    EXPECT_LE(r.residual, 1e-13) << "trial " << trial;
  }
}

TEST(Lemke, DegenerateSingularProblemsDoNotCycle) {
  // M = B Bᵀ with B n×k, k < n (singular, positive semidefinite), small integers so that ratios tie
  // exactly; q = w* − M z* with z*, w* ≥ 0, complementary, and both zero on some indices
  // (degenerate at the solution). A solution exists, so lexicographic Lemke must find one in few
  // pivots.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> small(-2, 2), pick(0, 2);
  int degenerate_seen = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 2 + trial % 7, k = 1 + trial % (n - 1);
    MatrixX B(n, k);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < k; ++j) B(i, j) = small(rng);
    const MatrixX M = B * B.transpose();
    VectorX zs = VectorX::Zero(n), ws = VectorX::Zero(n);
    int both_zero = 0;
    for (int i = 0; i < n; ++i) {
      const int c = pick(rng);
      if (c == 0)
        zs(i) = 1 + pick(rng);
      else if (c == 1)
        ws(i) = 1 + pick(rng);
      else
        ++both_zero;
    }
    degenerate_seen += both_zero > 0;
    const VectorX q = ws - M * zs;
    const LcpResult r = solve_lcp(M, q);
    ASSERT_TRUE(r.ok()) << "trial " << trial << ": " << to_string(r.status);
    EXPECT_LE(r.residual, 1e-12) << "trial " << trial;
    EXPECT_LE(r.pivots, 4 * n + 2) << "trial " << trial;
    // Symmetric PSD: w is the same at every solution.
    EXPECT_LE((r.w - ws).cwiseAbs().maxCoeff(), 1e-9) << "trial " << trial;
  }
  EXPECT_GT(degenerate_seen, 100);
}

TEST(Lemke, InfeasiblePsdProblemEndsOnASecondaryRay) {
  // z1 − z2 ≥ 1 and z2 − z1 ≥ 1 cannot both hold.
  MatrixX M(2, 2);
  M << 1, -1, -1, 1;
  const LcpResult r = solve_lcp(M, VectorX(Eigen::Vector2d(-1, -1)));
  EXPECT_EQ(r.status, LcpStatus::secondary_ray);
  EXPECT_FALSE(r.ok());
}

TEST(Lemke, SmallAndDynamicAgree) {
  MatT<kSmallLcp, kSmallLcp> Ms(3, 3);
  Ms << 2, -1, 0, -1, 2, -1, 0, -1, 2;
  VecT<kSmallLcp> qs(3);
  qs << -1, 3, -3;
  const SmallLcpResult a = solve_lcp(Ms, qs);
  const LcpResult b = solve_lcp(MatrixX(Ms), VectorX(qs));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(VectorX(a.z), b.z);
  EXPECT_EQ(a.pivots, b.pivots);
  // Hand check: z2 = 0 (w2 = 3 − z1 − z3 = 1 > 0), 2 z1 = 1, 2 z3 = 3.
  EXPECT_NEAR(a.z(0), 0.5, 1e-15);
  EXPECT_NEAR(a.z(2), 1.5, 1e-15);
}

// The LCP of a phase of Coulomb friction on a contacts (classical_phase.hpp, Anitescu & Potra's
// planar form): unknowns (P_N, P_T⁺, P_T⁻, λ) with P_T = P_T⁺ − P_T⁻ and λ the slip multiplier;
// G = WᵀW over the normal then the tangential columns, qN the normal velocities, vt the tangential
// ones, b the bounds' offsets.
template <class Mat, class Vec>
void frictional_lcp(const MatrixX& G, int a, double mu, const VectorX& qN, const VectorX& vt,
                    const VectorX& b, Mat& M, Vec& q) {
  const int n = 4 * a;
  M.setZero(n, n);
  q.resize(n);
  for (int i = 0; i < a; ++i) {
    for (int j = 0; j < a; ++j) {
      M(i, j) = G(i, j);
      M(i, a + j) = G(i, a + j);
      M(i, 2 * a + j) = -G(i, a + j);
      M(a + i, j) = G(a + i, j);
      M(a + i, a + j) = G(a + i, a + j);
      M(a + i, 2 * a + j) = -G(a + i, a + j);
      M(2 * a + i, j) = -G(a + i, j);
      M(2 * a + i, a + j) = -G(a + i, a + j);
      M(2 * a + i, 2 * a + j) = G(a + i, a + j);
    }
    M(a + i, 3 * a + i) = M(2 * a + i, 3 * a + i) = 1.0;
    M(3 * a + i, i) = mu;
    M(3 * a + i, a + i) = M(3 * a + i, 2 * a + i) = -1.0;
    q(i) = qN(i);
    q(a + i) = vt(i);
    q(2 * a + i) = -vt(i);
    q(3 * a + i) = b(i);
  }
}

// frictional_lcp on one to three contacts, with G = WᵀW from a random W of fewer rows than
// contact rows (G singular), zero columns, μ up to 10 and degenerate offsets (zeros). Its matrix is
// copositive but not copositive-plus, so where Lemke answers the answer must be an exact solution,
// and where the enumeration of complementary bases finds none Lemke must not claim one. The
// stack-stored and the heap-stored tableaux must pivot identically (same pivots, same z to the
// bit).
TEST(Lemke, FrictionalImpactLcpsAreSolvedExactly) {
  std::mt19937 rng(23);
  std::uniform_int_distribution<int> entry(-4, 4), pick(0, 4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int solved = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int a = 1 + trial % 3, dofs = 1 + trial % 4;
    MatrixX W(dofs, 2 * a);
    for (int i = 0; i < dofs; ++i)
      for (int j = 0; j < 2 * a; ++j) W(i, j) = pick(rng) == 0 ? 0.0 : 0.5 * entry(rng);
    const MatrixX G = W.transpose() * W;
    const double mu = pick(rng) == 0 ? 10.0 : 0.25 * (1 + pick(rng));
    VectorX qN(a), vt(a), b(a);
    for (int i = 0; i < a; ++i) {  // drawn in the order the test always drew them
      vt(i) = pick(rng) < 2 ? 0.0 : unit(rng);
      qN(i) = pick(rng) == 0 ? 0.0 : 0.5 * entry(rng);
      b(i) = pick(rng) < 3 ? 0.0 : std::fabs(unit(rng));
    }
    MatT<kSmallLcp, kSmallLcp> M;
    VecT<kSmallLcp> q;
    frictional_lcp(G, a, mu, qN, vt, b, M, q);
    const SmallLcpResult s = solve_lcp(M, q);
    const LcpResult d = solve_lcp(MatrixX(M), VectorX(q));
    ASSERT_EQ(s.status, d.status) << "trial " << trial;
    EXPECT_EQ(s.pivots, d.pivots) << "trial " << trial;
    if (!s.ok()) {
      EXPECT_TRUE(brute_force(MatrixX(M), VectorX(q)).empty() ||
                  s.status == LcpStatus::secondary_ray)
          << "trial " << trial;
      continue;
    }
    ++solved;
    EXPECT_EQ(VectorX(s.z), d.z) << "trial " << trial;
    EXPECT_LE(s.residual, 1e-12) << "trial " << trial;
    EXPECT_GE(s.z.minCoeff(), 0.0) << "trial " << trial;
    EXPECT_LE((s.w - (M * s.z + q)).cwiseAbs().maxCoeff(), 1e-12 * (1 + q.cwiseAbs().maxCoeff()))
        << "trial " << trial;
  }
  EXPECT_GT(solved, 400);
}

// Many contacts of a planar body (3 dofs): G of rank 3 and 64 to 128 unknowns, where most
// pivots have a pivot row of mostly zeros and the elimination visits only its non-zero columns.
// The answer is checked against its own definition: z ≥ 0, w = Mz + q ≥ 0 recomputed here, zᵀw = 0.
TEST(Lemke, ManyContactFrictionalLcpsSatisfyTheComplementarityConditions) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int pivots = 0;
  for (const int a : {16, 24, 32}) {
    for (int trial = 0; trial < 4; ++trial) {
      // A flat plate at q̇ = (x, y, θ): normals (0, 1, x_i), tangents (1, 0, s_i), s_i = 0 or small.
      MatrixX W(3, 2 * a);
      for (int i = 0; i < a; ++i) {
        W.col(i) << 0.0, 1.0, -1.0 + 2.0 * i / (a - 1);
        W.col(a + i) << 1.0, 0.0, trial % 2 ? 0.1 * unit(rng) : 0.0;
      }
      const MatrixX G = W.transpose() * W;
      VectorX qN(a), vt(a), b = VectorX::Zero(a);
      const double slope = 0.5 * unit(rng), x_dot = trial < 2 ? 0.7 : 0.0;
      for (int i = 0; i < a; ++i) {
        qN(i) = -1.0 + slope * W(2, i);  // every contact approaches
        vt(i) = x_dot + W(2, a + i);
      }
      MatrixX M;
      VectorX q;
      frictional_lcp(G, a, 0.3, qN, vt, b, M, q);
      const LcpResult r = solve_lcp(M, q);
      ASSERT_EQ(r.status, LcpStatus::solved) << a << " contacts, trial " << trial;
      pivots += r.pivots;
      const VectorX w = M * r.z + q;
      const double scale =
          q.cwiseAbs().maxCoeff() + M.cwiseAbs().maxCoeff() * r.z.cwiseAbs().maxCoeff();
      EXPECT_GE(r.z.minCoeff(), 0.0) << a << " contacts, trial " << trial;
      EXPECT_GE(w.minCoeff(), -1e-13 * scale) << a << " contacts, trial " << trial;
      EXPECT_LE(r.z.cwiseProduct(w).cwiseAbs().maxCoeff(),
                1e-13 * scale * (1.0 + r.z.cwiseAbs().maxCoeff()))
          << a << " contacts, trial " << trial;
      EXPECT_LE(r.residual, 1e-13) << a << " contacts, trial " << trial;
    }
  }
  EXPECT_GT(pivots, 12 * 16);  // the problems are not solved by a pivot or two
}

TEST(Lemke, RefusesBadInput) {
  EXPECT_THROW(solve_lcp(MatrixX(2, 3), VectorX(2)), InvalidArgument);
  MatrixX M = MatrixX::Identity(2, 2);
  M(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(solve_lcp(M, VectorX(Eigen::Vector2d(-1, 1))), InvalidArgument);
  LemkeOptions bad;
  bad.max_pivots = 0;
  EXPECT_THROW(solve_lcp(MatrixX(MatrixX::Identity(1, 1)), VectorX(VectorX::Ones(1)), bad),
               InvalidArgument);
  EXPECT_EQ(lcp_status_from_string("secondary_ray"), LcpStatus::secondary_ray);
  EXPECT_THROW(lcp_status_from_string("nope"), InvalidArgument);
}

}  // namespace
}  // namespace fremond
