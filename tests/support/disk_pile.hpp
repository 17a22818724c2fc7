#pragma once
/// @file A pile of disks: a sparse impact problem of any size with more contact rows than degrees
/// of freedom, shared by the sparse solver's tests and benchmark.
#include <Eigen/SparseCore>
#include <random>
#include <vector>

#include "fremond/sparse/sparse_problem.hpp"

namespace fremond::fixtures {

// A pile of `columns` × `layers` equal disks (radius 0.5, m = 1, J = 1/8) in a square packing on
// the ground, every neighbour touching: (columns − 1) layers contacts side by side, columns
// (layers − 1) one above another, columns on the ground, more contact rows than degrees of freedom
// (G singular, as in granular media). The disks fall at about 1 m/s with random spreads (seeded),
// Newton + Coulomb, e = 0, μ = 0.5: the cost of a solve against the number of contacts, for piles
// that grow in height (square) or in width only (a bed of a few layers).
inline SparseImpactProblem disk_pile(int columns, int layers) {
  const int disks = columns * layers, n = 3 * disks;
  auto at = [columns](int i, int j) { return 3 * (j * columns + i); };  // column i, layer j
  std::vector<Eigen::Triplet<double>> M, WN, WT;
  for (int d = 0; d < disks; ++d) {
    M.emplace_back(3 * d, 3 * d, 1.0);
    M.emplace_back(3 * d + 1, 3 * d + 1, 1.0);
    M.emplace_back(3 * d + 2, 3 * d + 2, 0.125);
  }
  int c = 0;
  // Contact of disk b on disk a along the unit normal (nx, ny) from a to b; tangent (−ny, nx);
  // the contact point's velocity on each disk is v + ω × (±r n).
  auto touch = [&](int a, int b, double nx, double ny) {
    const double r = 0.5, tx = -ny, ty = nx;
    WN.emplace_back(b, c, nx);
    WN.emplace_back(b + 1, c, ny);
    WT.emplace_back(b, c, tx);
    WT.emplace_back(b + 1, c, ty);
    WT.emplace_back(b + 2, c, -r);  // ω × (−r n) of b, along t
    if (a >= 0) {
      WN.emplace_back(a, c, -nx);
      WN.emplace_back(a + 1, c, -ny);
      WT.emplace_back(a, c, -tx);
      WT.emplace_back(a + 1, c, -ty);
      WT.emplace_back(a + 2, c, -r);  // minus ω × (r n) of a, along t
    }
    ++c;
  };
  for (int j = 0; j < layers; ++j)
    for (int i = 0; i < columns; ++i) {
      if (i > 0) touch(at(i - 1, j), at(i, j), 1.0, 0.0);
      touch(j > 0 ? at(i, j - 1) : -1, at(i, j), 0.0, 1.0);
    }
  SparseImpactProblem pb;
  pb.M.resize(n, n);
  pb.M.setFromTriplets(M.begin(), M.end());
  pb.W_N.resize(n, c);
  pb.W_N.setFromTriplets(WN.begin(), WN.end());
  pb.W_T.resize(n, c);
  pb.W_T.setFromTriplets(WT.begin(), WT.end());
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  pb.qdot_A.resize(n);
  for (int d = 0; d < disks; ++d) {
    pb.qdot_A(3 * d) = 0.1 * u(rng);
    pb.qdot_A(3 * d + 1) = -1.0 + 0.2 * u(rng);
    pb.qdot_A(3 * d + 2) = 0.5 * u(rng);
  }
  return pb;
}

// The square pile of s × s disks: 2s² − s contacts.
inline SparseImpactProblem disk_pile(int s) {
  return disk_pile(s, s);
}

}  // namespace fremond::fixtures
