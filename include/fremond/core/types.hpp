#pragma once
/// @file Basic scalar, vector and matrix types.
///
/// Every problem type is a template on two *maximum* sizes (degrees of freedom, contacts). A
/// maximum of `Eigen::Dynamic` stores on the heap; a finite maximum stores on the stack, so a solve
/// of a small problem (a planar body with up to four contacts) performs no heap allocation.
#include <Eigen/Core>

namespace fremond {

using Scalar = double;
inline constexpr int Dynamic = Eigen::Dynamic;

/// Maxima of the stack-stored "small" problems: a body with up to 6 degrees of freedom and up to 4
/// contacts (8 contact rows in the plane).
inline constexpr int kSmallDofs = 6;
inline constexpr int kSmallContacts = 4;

namespace detail {
constexpr int times2(int m) {
  return m == Dynamic ? Dynamic : 2 * m;
}
}  // namespace detail

/// A column vector of dynamic size bounded by Max (heap when Max is Dynamic).
template <int Max>
using VecT = Eigen::Matrix<Scalar, Eigen::Dynamic, 1, Eigen::ColMajor, Max, 1>;
/// A matrix of dynamic size bounded by MaxR x MaxC.
template <int MaxR, int MaxC>
using MatT = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, MaxR, MaxC>;

using VectorX = Eigen::VectorXd;
using MatrixX = Eigen::MatrixXd;

}  // namespace fremond
