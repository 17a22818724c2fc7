#include "fremond/potentials/conformance.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace fremond {

namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// Minimiser of the convex h(u) = φ*(u) + (τ/2)(u − w)² by golden-section search on a bracket that
// contains it: the conjugate's prox, computed without the potential's own prox.
double conjugate_prox_by_search(const Potential& f, double w, double tau, double hint) {
  auto h = [&](double u) {
    const double c = f.conjugate(u);
    return std::isinf(c) ? std::numeric_limits<double>::infinity()
                         : c + 0.5 * tau * (u - w) * (u - w);
  };
  const double span = 4.0 * (1.0 + std::fabs(w) + std::fabs(hint));
  double a = hint - span, b = hint + span;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double hc = h(c), hd = h(d);
  for (int i = 0; i < 300 && (b - a) > 1e-15 * (1.0 + std::fabs(a) + std::fabs(b)); ++i) {
    // Ties (both +∞ or equal) shrink towards the hint so the bracket keeps the finite part.
    if (hc < hd || (hc == hd && std::fabs(c - hint) < std::fabs(d - hint))) {
      b = d;
      d = c;
      hd = hc;
      c = b - g * (b - a);
      hc = h(c);
    } else {
      a = c;
      c = d;
      hc = hd;
      d = a + g * (b - a);
      hd = h(d);
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

std::string ConformanceReport::summary() const {
  std::ostringstream os;
  os << (ok ? "conforms" : "DOES NOT CONFORM") << " (" << checks << " checks";
  if (!failures.empty()) os << ", " << failures.size() << " failures; first: " << failures.front();
  os << ")";
  return os.str();
}

ConformanceReport check_potential(const Potential& f, const ConformanceOptions& opt) {
  ConformanceReport rep;
  const auto caps = f.capabilities();
  auto fail = [&](std::string s) {
    rep.ok = false;
    if (rep.failures.size() < 20) rep.failures.push_back(std::move(s));
  };
  auto check = [&](bool cond, const std::string& what) {
    ++rep.checks;
    if (!cond) fail(what);
  };
  std::mt19937_64 rng(opt.seed);
  std::uniform_real_distribution<double> uni(-opt.range, opt.range);
  std::uniform_real_distribution<double> expo(-6.0, 0.0);
  std::vector<double> pts{0.0, 1e-12, -1e-12, opt.range, -opt.range};
  for (int i = 0; i < opt.samples; ++i) {
    pts.push_back(uni(rng));
    pts.push_back((i % 2 ? 1 : -1) * opt.range * std::pow(10.0, expo(rng)));
  }
  const double tol = opt.tolerance;

  check(std::fabs(f.value(0.0)) <= tol, "phi(0) = " + fmt(f.value(0.0)) + ", must be 0");
  for (double z : pts) {
    const double v = f.value(z);
    check(v >= -tol * (1.0 + std::fabs(z)), "phi(" + fmt(z) + ") = " + fmt(v) + " < 0");
  }
  // Convexity on chords and the subgradient inequality φ(w) ≥ φ(z) + g(w − z).
  for (std::size_t i = 0; i + 1 < pts.size(); i += 2) {
    const double a = pts[i], b = pts[i + 1], t = 0.3;
    const double fa = f.value(a), fb = f.value(b), fm = f.value(t * a + (1 - t) * b);
    if (std::isfinite(fa) && std::isfinite(fb)) {
      const double scale = 1.0 + std::fabs(fa) + std::fabs(fb);
      check(fm <= t * fa + (1 - t) * fb + tol * scale,
            "not convex on [" + fmt(a) + ", " + fmt(b) + "]");
      const double g = f.subgradient(a);
      if (std::isfinite(g))
        check(fb >= fa + g * (b - a) - tol * (scale + std::fabs(g * (b - a))),
              "subgradient inequality fails at z=" + fmt(a) + ", w=" + fmt(b));
    }
  }
  if (caps.prox) {
    for (double tau : opt.taus) {
      double prev_x = 0, prev_y = 0;
      bool have_prev = false;
      for (double x : pts) {
        double d = -1.0;
        const double y = f.prox(x, tau, &d);
        double s = (x - y) / tau;
        if (caps.conjugate && std::isinf(f.conjugate(s))) {
          // s = (x − y)/τ carries the rounding of x − y; step it back by that much, so that a
          // conjugate that is an indicator (|s| ≤ b) is not judged on the last bits.
          const double round =
              16 * std::numeric_limits<double>::epsilon() * (std::fabs(x) + std::fabs(y)) / tau;
          s -= std::copysign(std::min(round, std::fabs(s)), s);
        }
        const double scale = 1.0 + std::fabs(x);
        check(std::isfinite(y), "prox(" + fmt(x) + ", " + fmt(tau) + ") is not finite");
        check(d >= -tol && d <= 1.0 + tol,
              "prox derivative " + fmt(d) + " outside [0,1] at x=" + fmt(x));
        if (caps.subdifferential) {
          // y is the exact prox rounded: s must lie in ∂φ somewhere within y's rounding. ∂φ is
          // monotone, so over [y − δ, y + δ] it spans [lo ∂φ(y − δ), hi ∂φ(y + δ)]; at a kink
          // (|z| at 0) a prox of 2e-29 for the exact 0 then meets the whole interval there.
          const double delta =
              64 * std::numeric_limits<double>::epsilon() * (std::fabs(x) + std::fabs(y)) +
              std::numeric_limits<double>::denorm_min();
          Interval near = f.subdifferential(y);
          const Interval below = f.subdifferential(y - delta), above = f.subdifferential(y + delta);
          if (!below.is_empty() && !above.is_empty() && !near.is_empty())
            near = {std::min(near.lo, below.lo), std::max(near.hi, above.hi)};
          const double dist = near.distance(s) * tau / scale;
          rep.max_prox_optimality = std::max(rep.max_prox_optimality, dist);
          check(dist <= 1e-6, "prox optimality (x-y)/tau in dphi(y) fails at x=" + fmt(x) +
                                  ", tau=" + fmt(tau) + " (distance " + fmt(dist) + ")");
        }
        if (have_prev) {  // firm non-expansiveness: (y1−y2)(x1−x2) ≥ (y1−y2)²
          const double dy = y - prev_y, dx = x - prev_x;
          check(dy * dx >= dy * dy - tol * (1.0 + dx * dx),
                "prox not firmly non-expansive between x=" + fmt(prev_x) + " and " + fmt(x));
        }
        if (caps.prox_derivative && std::fabs(x) > 1e-3) {
          const double h = 1e-6 * std::fabs(x);
          const double fd = (f.prox(x + h, tau) - f.prox(x - h, tau)) / (2 * h);
          // At kinks of the prox the one-sided slopes differ; allow either of them.
          const double fr = (f.prox(x + h, tau) - y) / h, fl = (y - f.prox(x - h, tau)) / h;
          const bool near =
              std::fabs(fd - d) <= 1e-3 || std::fabs(fr - d) <= 1e-3 || std::fabs(fl - d) <= 1e-3;
          check(near, "prox derivative " + fmt(d) + " disagrees with the finite difference " +
                          fmt(fd) + " at x=" + fmt(x) + ", tau=" + fmt(tau));
        }
        if (caps.conjugate) {
          const double gap = f.fenchel_young_gap(y, s);
          const double gscale = 1.0 + std::fabs(s * y) + std::fabs(f.value(y));
          rep.max_fenchel_young_gap_at_prox =
              std::max(rep.max_fenchel_young_gap_at_prox, gap / gscale);
          check(std::fabs(gap) <= 1e-8 * gscale,
                "Fenchel-Young gap " + fmt(gap) + " at the prox point of x=" + fmt(x));
          const double u = conjugate_prox_by_search(f, x / tau, tau, s);
          const double err = std::fabs(u - s) * tau / scale;
          rep.max_moreau_error = std::max(rep.max_moreau_error, err);
          check(err <= 1e-6, "Moreau identity fails at x=" + fmt(x) + ", tau=" + fmt(tau) +
                                 ": prox of the conjugate " + fmt(u) + " vs " + fmt(s));
        }
        prev_x = x;
        prev_y = y;
        have_prev = true;
      }
    }
  }
  if (caps.conjugate) {
    for (std::size_t i = 0; i + 1 < pts.size(); i += 2) {
      const double z = pts[i], s = pts[i + 1];
      const double gap = f.fenchel_young_gap(z, s);
      check(
          gap >= -tol * (1.0 + std::fabs(s * z)),
          "Fenchel-Young inequality fails: gap " + fmt(gap) + " at z=" + fmt(z) + ", s=" + fmt(s));
    }
  }
  return rep;
}

}  // namespace fremond
