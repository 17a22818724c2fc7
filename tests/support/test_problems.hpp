#pragma once
// Problems of the tests beside the shared fixtures (fixtures.hpp, which this brings into
// fremond::testing): random problems with a fixed seed (random SPD M, random contact directions,
// some contacts taking part), detached separating contacts, and a case every method finds hard.
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/QR>

#include "fremond/fremond.hpp"
#include "support/fixtures.hpp"

namespace fremond::testing {

using namespace fremond::fixtures;  // the bar, the flat bar, the plate, the point masses

/// A random problem: n dofs, c contacts, M = AᵀA + δI with condition up to `cond`, directions of
/// unit scale, velocities of scale `vscale`; at least one contact takes part.
inline ImpactProblem random_problem(std::mt19937_64& rng, int n, int c, bool tangential,
                                    double cond = 1e3, double vscale = 1.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ImpactProblem pb;
  MatrixX A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  Eigen::HouseholderQR<MatrixX> qr(A);
  const MatrixX Q = qr.householderQ();
  VectorX d(n);
  for (int i = 0; i < n; ++i) d(i) = std::pow(cond, 0.5 * (u(rng) + 1.0) * (n > 1 ? 1.0 : 0.0));
  pb.M = Q * d.asDiagonal() * Q.transpose();
  pb.M = 0.5 * (pb.M + pb.M.transpose()).eval();
  pb.W_N.resize(n, c);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < c; ++j) pb.W_N(i, j) = u(rng);
  if (tangential) {
    pb.W_T.resize(n, c);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < c; ++j) pb.W_T(i, j) = u(rng);
  }
  pb.qdot_A.resize(n);
  for (int i = 0; i < n; ++i) pb.qdot_A(i) = vscale * u(rng);
  // Make the first contact approach.
  const double dn = pb.W_N.col(0).dot(pb.qdot_A);
  if (dn > 0.0) pb.qdot_A -= (2.0 * dn / pb.W_N.col(0).squaredNorm()) * pb.W_N.col(0);
  return pb;
}

/// The problem with its contacts that separate before the impact (D_NA > 0) detached from the
/// body: W_N and W_T columns zero, w_N = D_NA and w_T = D_TA, so that nothing can drive them and
/// they leave as they came. That is the impact as it was solved before every contact took part
/// (docs/concepts.md): regression cases found on that convention keep their numerical point, and
/// their contacts' indices.
inline ImpactProblem detach_separating(const ImpactProblem& pb) {
  ImpactProblem out = pb;
  const int c = pb.contacts();
  if (out.w_N.size() == 0) out.w_N = VectorX::Zero(c);
  if (pb.has_tangential() && out.w_T.size() == 0) out.w_T = VectorX::Zero(c);
  for (int i = 0; i < c; ++i) {
    const double d = pb.W_N.col(i).dot(pb.qdot_A) + (pb.w_N.size() ? pb.w_N(i) : 0.0);
    if (!(d > 0.0)) continue;
    out.w_N(i) = d;
    out.W_N.col(i).setZero();
    if (pb.has_tangential()) {
      out.w_T(i) = pb.W_T.col(i).dot(pb.qdot_A) + (pb.w_T.size() ? pb.w_T(i) : 0.0);
      out.W_T.col(i).setZero();
    }
  }
  return out;
}

/// Four contacts on three dofs, cond(M) = 1e10, speeds 1e-9, p from 1.003 to 31 with the viscous
/// dead zone (fremond_viscous #63 of stress seed 23): a case where every method of Frémond's chain
/// fails or nearly, NLopt's end 9e12 of the velocities from the law.
struct HardFremondCase {
  ImpactProblem problem;
  ImpactLaw law;
};
inline HardFremondCase every_method_failing_case() {
  HardFremondCase c;
  ImpactProblem& pb = c.problem;
  pb.M.resize(3, 3);
  pb.M << 7951828.996842298, -16449933.183492143, 9020740.580749638, -16449933.183492143,
      34029946.10497301, -18661189.926689938, 9020740.580749638, -18661189.926689938,
      10233340.4170277;
  pb.W_N.resize(3, 4);
  pb.W_N << 0.9253293531650559, -0.5210114094630116, -0.8952477121556833, 0.9253293531650559,
      0.7692881614889511, 0.9739469124269164, 0.6066104889029429, 0.7692881614889511,
      0.9365482111065937, 0.1497906745901345, -0.7662332784780111, 0.9365482111065937;
  pb.W_T.resize(3, 4);
  pb.W_T << 0.2652742867339486, 0.6506144198035824, -0.028944442760205358, -0.015426005738093607,
      0.7485155773358516, 0.7430756335658784, -0.46716201977964655, 0.1842153471431538,
      -0.7941066387828781, -0.2129325428485339, -0.6341555452713468, -0.5201974050901444;
  pb.qdot_A =
      Eigen::Vector3d(3.643957871526755e-09, -3.3323752925316983e-09, -3.5348621602472427e-09);
  const double k[4] = {6.359817502633181, 66113.18883090747, 3005.291157828727, 3579.2234395360924};
  const double p[4] = {5.914055754085484, 31.137382733915185, 1.003390763568152, 2.403721887609679};
  PerContactPotential normal;
  for (int i = 0; i < 4; ++i)
    normal.potentials.emplace_back(std::make_unique<PowerPotential>(k[i], p[i]));
  c.law = ImpactLaw::fremond(
      std::move(normal),
      DeadZonePowerPotential(106.18344232384078, 4.973125386008597, 3.0569394144157536e-09));
  return c;
}

}  // namespace fremond::testing
