// The contact space of a diagonal mass matrix (src/contact_space/contact_space.hpp): the fixed-size
// path that the planar and spatial bodies and the point masses take gives the general path's
// numbers to the last bit, in every member; its M⁻¹W and G are the exact ones to rounding
// (against long double sums); and where it cannot apply (an overflow, a pivot that is not
// positive) the general path's refusal is what the caller sees.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "contact_space/contact_space.hpp"
#include "fremond/core/error.hpp"

namespace {

using namespace fremond;
using Space = detail::ContactSpaceT<kSmallDofs, kSmallContacts>;

std::uint64_t bits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

template <class A, class B>
void expect_same_bits(const A& a, const B& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      EXPECT_EQ(bits(a(i, j)), bits(b(i, j)))
          << what << "(" << i << "," << j << "): " << a(i, j) << " vs " << b(i, j);
}

void expect_same(const Space& fast, const Space& general) {
  EXPECT_EQ(fast.dofs, general.dofs);
  EXPECT_EQ(fast.contacts, general.contacts);
  EXPECT_EQ(fast.active, general.active);
  EXPECT_EQ(fast.tangential, general.tangential);
  ASSERT_EQ(fast.index.size(), general.index.size());
  for (Eigen::Index k = 0; k < fast.index.size(); ++k) EXPECT_EQ(fast.index(k), general.index(k));
  expect_same_bits(fast.W, general.W, "W");
  expect_same_bits(fast.MinvW, general.MinvW, "MinvW");
  expect_same_bits(fast.G, general.G, "G");
  expect_same_bits(fast.D_A, general.D_A, "D_A");
  expect_same_bits(fast.D_N, general.D_N, "D_N");
  expect_same_bits(fast.D_T, general.D_T, "D_T");
  EXPECT_EQ(bits(fast.v_scale), bits(general.v_scale));
  EXPECT_EQ(fast.llt.info(), general.llt.info());
  EXPECT_EQ(fast.llt.matrix_is_diagonal(), general.llt.matrix_is_diagonal());
  const auto& Lf = fast.llt.matrixLLT();
  const auto& Lg = general.llt.matrixLLT();
  ASSERT_EQ(Lf.rows(), Lg.rows());
  for (Eigen::Index i = 0; i < Lf.rows(); ++i)
    EXPECT_EQ(bits(Lf(i, i)), bits(Lg(i, i))) << "L(" << i << "," << i << ")";
}

// A random problem with a diagonal M over twelve decades, contacts that take part or not
// (D_NA of either sign, and exactly zero), with or without tangential rows and obstacle terms.
SmallImpactProblem random_diagonal_problem(int n, int c, bool tangential, std::mt19937_64& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), decade(-6.0, 6.0);
  SmallImpactProblem pb;
  pb.M.setZero(n, n);
  for (int i = 0; i < n; ++i) pb.M(i, i) = std::pow(10.0, decade(gen));
  pb.W_N.resize(n, c);
  pb.W_T.resize(n, tangential ? c : 0);
  for (int j = 0; j < c; ++j)
    for (int i = 0; i < n; ++i) {
      pb.W_N(i, j) = u(gen) * std::pow(10.0, decade(gen) / 3);
      if (tangential) pb.W_T(i, j) = u(gen);
    }
  pb.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) pb.qdot_A(i) = u(gen) * std::pow(10.0, decade(gen) / 2);
  if (gen() % 3 == 0) {
    pb.w_N.resize(c);
    for (int j = 0; j < c; ++j) pb.w_N(j) = u(gen);
  }
  if (tangential && gen() % 3 == 0) {
    pb.w_T.resize(c);
    for (int j = 0; j < c; ++j) pb.w_T(j) = u(gen);
  }
  if (gen() % 5 == 0) pb.W_N.col(0).setZero();  // D_NA = 0 exactly: takes part
  return pb;
}

TEST(ContactSpace, DiagonalMassFixedSizePathIsTheGeneralPathToTheLastBit) {
  std::mt19937_64 gen(20261202);
  int fixed_sizes = 0, partly_active = 0, none_active = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int n = 1 + trial % kSmallDofs;  // 4 and 5 take the general path in both calls
    const int c = 1 + (trial / kSmallDofs) % kSmallContacts;
    for (const bool tangential : {false, true})
      for (const bool with_tangential : {false, true}) {
        const SmallImpactProblem pb = random_diagonal_problem(n, c, tangential, gen);
        SCOPED_TRACE("trial " + std::to_string(trial) + ", n = " + std::to_string(n) +
                     ", c = " + std::to_string(c));
        Space fast, general;
        const bool took_fixed =
            detail::contact_space_detail::build_diagonal(pb, with_tangential, fast);
        EXPECT_EQ(took_fixed, n == 1 || n == 2 || n == 3 || n == 6);
        detail::build_contact_space(pb, with_tangential, fast);
        detail::build_contact_space_general(pb, with_tangential, general);
        expect_same(fast, general);
        fixed_sizes += took_fixed;
        partly_active += fast.active > 0 && fast.active < c;
        none_active += fast.active == 0;
        if (HasFailure()) return;
      }
  }
  // The draws reach what the comparison must cover.
  EXPECT_GT(fixed_sizes, 8000);
  EXPECT_GT(partly_active, 1000);
  EXPECT_GT(none_active, 100);
}

TEST(ContactSpace, DiagonalMassInverseAndDelassusAreTheExactOnesToRounding) {
  std::mt19937_64 gen(7);
  const double eps = std::numeric_limits<double>::epsilon();
  for (int trial = 0; trial < 3000; ++trial) {
    const int n = std::array{1, 2, 3, 6}[trial % 4];
    const int c = 1 + (trial / 4) % kSmallContacts;
    SmallImpactProblem pb = random_diagonal_problem(n, c, true, gen);
    for (int j = 0; j < c; ++j)
      if (pb.W_N.col(j).dot(pb.qdot_A) + (pb.w_N.size() ? pb.w_N(j) : 0.0) > 0.0)
        pb.qdot_A = -pb.qdot_A;  // keep most contacts taking part
    Space cs;
    detail::build_contact_space(pb, true, cs);
    for (int j = 0; j < cs.rows(); ++j) {
      for (int i = 0; i < n; ++i) {
        // One rounding: within half an ulp of W_ij / m_i.
        const long double exact =
            static_cast<long double>(cs.W(i, j)) / static_cast<long double>(pb.M(i, i));
        EXPECT_LE(std::fabs(static_cast<long double>(cs.MinvW(i, j)) - exact),
                  0.5L * eps * std::fabs(exact) * (1 + 1e-3L))
            << trial;
      }
      for (int k = 0; k < cs.rows(); ++k) {
        long double exact = 0.0L, size = 0.0L;
        for (int i = 0; i < n; ++i) {
          const long double t = static_cast<long double>(cs.W(i, j)) * cs.W(i, k) / pb.M(i, i);
          exact += t;
          size += std::fabs(t);
        }
        // Two roundings per term and n − 1 additions: (n + 2) ε of the terms' sizes.
        EXPECT_LE(std::fabs(static_cast<long double>(cs.G(j, k)) - exact), (n + 2) * eps * size)
            << trial << " G(" << j << "," << k << ")";
        EXPECT_EQ(cs.G(j, k), cs.G(k, j));
      }
    }
    if (HasFailure()) return;
  }
}

TEST(ContactSpace, DiagonalMassOverflowIsTheGeneralPathsRefusal) {
  // |W|²/|M| beyond 1e308: the fixed-size path gives up and the general one names the column.
  SmallImpactProblem pb;
  pb.M = Eigen::Vector3d(1e-10, 1e-10, 1e-10).asDiagonal();
  pb.W_N = Eigen::Vector3d(0.0, 1e160, 0.0);
  pb.W_T = Eigen::Vector3d(1.0, 0.0, 0.0);
  pb.qdot_A = Eigen::Vector3d(0.0, -1e-200, 0.0);
  Space cs;
  EXPECT_FALSE(detail::contact_space_detail::build_diagonal(pb, true, cs));
  try {
    detail::build_contact_space(pb, true, cs);
    ADD_FAILURE() << "an overflowing Delassus entry was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(e.name(), "W_N");
    EXPECT_NE(std::string(e.what()).find("overflows"), std::string::npos) << e.what();
  }
}

TEST(ContactSpace, DiagonalMassWithAPivotThatIsNotPositiveTakesTheGeneralPath) {
  for (const double m : {0.0, -1.0}) {
    SmallImpactProblem pb;
    pb.M = Eigen::Vector3d(1.0, m, 1.0).asDiagonal();
    pb.W_N = Eigen::Vector3d(0.0, 1.0, 0.0);
    pb.W_T.resize(3, 0);
    pb.qdot_A = Eigen::Vector3d(0.0, -1.0, 0.0);
    Space cs;
    EXPECT_FALSE(detail::contact_space_detail::build_diagonal(pb, false, cs)) << m;
    // The general path refuses M at once where a row's entries overflow (W/0), or leaves the
    // failed factor that solve_impact then refuses as M's.
    try {
      detail::build_contact_space(pb, false, cs);
      EXPECT_NE(cs.llt.info(), Eigen::Success) << m;
    } catch (const InvalidArgument& e) {
      EXPECT_EQ(e.name(), "M") << m << ": " << e.what();
    }
  }
}

TEST(ContactSpace, DiagonalMassGivesTheSameBitsInEitherStorage) {
  // A heap-stored problem too big for the stack (two bodies of one problem each, stress's
  // independent-groups copy) must see the Delassus entries of its parts as stored on the stack: a
  // singular G makes the answer sensitive to their last bits.
  std::mt19937_64 gen(41);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + trial % kSmallDofs;
    const int c = 1 + (trial / kSmallDofs) % kSmallContacts;
    const SmallImpactProblem pb = random_diagonal_problem(n, c, trial % 2 == 0, gen);
    const ImpactProblem heap = to_dynamic(pb);
    Space small;
    detail::ContactSpaceT<Dynamic, Dynamic> big;
    detail::build_contact_space(pb, true, small);
    detail::build_contact_space(heap, true, big);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_same_bits(small.G, big.G, "G");
    expect_same_bits(small.MinvW, big.MinvW, "MinvW");
    expect_same_bits(small.D_A, big.D_A, "D_A");
    if (HasFailure()) return;
  }
}

}  // namespace
