#pragma once
/// @file Impacts of balls in a line, the cases where multiple-impact laws differ (docs/stronge.md):
/// Newton's cradle, a chain of equal balls struck at one end, and a ball dropped on one resting on
/// the ground. The impact problem only: q = the balls' positions along the line, M = diag(m),
/// one contact between each pair of neighbours and, with `ground`, one between the first ball and
/// a fixed ground below it.
#include <span>

#include "fremond/core/impact_problem.hpp"

namespace fremond {

/// The impact of balls i = 0..n−1 in a line, ball i + 1 after ball i, with velocities `velocity`
/// along the line at the instant every neighbour touches. Contact k < n − 1 is between balls k and
/// k + 1: D_N = v_{k+1} − v_k (> 0 separating), so W_N's column k is −1 at ball k and +1 at ball
/// k + 1. With `ground`, a last contact holds ball 0 off a fixed ground behind it: D_N = v_0.
/// Frictionless (W_T has no column). Throws InvalidArgument naming `masses` (fewer than one, or
/// not finite and > 0) or `velocity` (not one per ball, or not finite).
ImpactProblem ball_chain(std::span<const double> masses, std::span<const double> velocity,
                         bool ground = false);

}  // namespace fremond
