// The extended-precision Delassus matrix of the classical laws' last resort
// (decide_in_extended_precision in src/solvers/detail/classical_law.hpp), against the quad
// reference's G = Wᵀ M⁻¹ W of the same double data.
//
// A Cholesky solve in extended precision alone leaves cond(M)·ε_extended in M⁻¹W (1e-7 at
// cond(M) = 1e12); refined against residuals summed in twice double precision, G must come out
// to the extended format's own rounding, far below double's, whatever cond(M) up to 1e12.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "fremond/fremond.hpp"
#include "reference/fremond_reference.hpp"
#include "solvers/detail/classical_law.hpp"

namespace fremond {
namespace {

namespace ref = fremond_reference;
namespace classical = detail::classical;

/// A dense SPD 3×3 M = Q diag(1, √cond, cond) Qᵀ with a random rotation Q, rounded to double.
Eigen::Matrix3d random_mass(double cond, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
  const Eigen::Matrix3d Q = q.normalized().toRotationMatrix();
  const Eigen::Vector3d lambda(1.0, std::sqrt(cond), cond);
  const Eigen::Matrix3d M = Q * lambda.asDiagonal() * Q.transpose();
  return 0.5 * (M + M.transpose());
}

TEST(ExtendedDelassus, AgreesWithTheQuadReferenceToTheExtendedRounding) {
  if constexpr (!classical::kHaveExtended) GTEST_SKIP() << "long double is double here";
  std::mt19937 rng(20261128);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst_extended = 0.0, worst_double = 0.0;
  int compared = 0;
  for (const double cond : {1e2, 1e6, 1e9, 1e10, 1e11, 1e12}) {
    for (int trial = 0; trial < 20; ++trial) {
      ImpactProblem pb;
      pb.M = random_mass(cond, rng) * std::pow(10.0, 4 * u(rng));
      pb.W_N = MatrixX::NullaryExpr(3, 3, [&] { return u(rng); });
      pb.W_T = MatrixX::NullaryExpr(3, 3, [&] { return u(rng); });
      pb.qdot_A = -pb.M.ldlt().solve(pb.W_N * Eigen::Vector3d::Ones());  // every contact closing
      detail::ContactSpaceT<Dynamic, Dynamic> cs;
      detail::build_contact_space(pb, true, cs);
      const int a = cs.active, r = 2 * a;
      if (a == 0) continue;
      classical::MatS<Dynamic, Dynamic, classical::Extended> G;
      ASSERT_TRUE(classical::extended_delassus(pb, cs, r, G));
      const auto d = ref::detail::contact_data(ref::problem_from(pb.M, pb.W_N, pb.W_T, pb.qdot_A));
      // Row j of the contact space: contact cs.index(j mod a), normal for j < a.
      auto reference = [&](int j, int k) {
        const int cj = cs.index(j % a), ck = cs.index(k % a);
        if (j < a && k < a) return d.GNN(cj, ck);
        if (j < a) return d.GNT(cj, ck);
        if (k < a) return d.GNT(ck, cj);
        return d.GTT(cj, ck);
      };
      double scale = 0.0;
      for (int j = 0; j < r; ++j) scale = std::max(scale, ref::to_double(reference(j, j)));
      double err_extended = 0.0, err_double = 0.0;
      for (int j = 0; j < r; ++j)
        for (int k = 0; k < r; ++k) {
          const ref::quad exact = reference(j, k);
          err_extended =
              std::max(err_extended, std::fabs(ref::to_double(ref::quad(G(j, k)) - exact)) / scale);
          err_double = std::max(err_double,
                                std::fabs(ref::to_double(ref::quad(cs.G(j, k)) - exact)) / scale);
        }
      worst_extended = std::max(worst_extended, err_extended);
      worst_double = std::max(worst_double, err_double);
      ++compared;
      // The extended format's ε is 1.1e-19; a few units of it, relative to G's largest entry.
      EXPECT_LE(err_extended, 64 * std::numeric_limits<classical::Extended>::epsilon())
          << "cond(M) = " << cond << ", trial " << trial << " (double's G: " << err_double << ")";
    }
  }
  EXPECT_GE(compared, 100);
  // Double's G, refined too, is good to its own ε (about 1e-16 here): the extended one is finer by
  // the ratio of the formats' rounding, which is what lets a mode's singular values of 1e-15 be
  // read.
  EXPECT_GT(worst_double, 100 * worst_extended)
      << "double " << worst_double << ", extended " << worst_extended;
}

}  // namespace
}  // namespace fremond
