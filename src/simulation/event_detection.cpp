// Exhaustive event search on the closed-form gap of a free flight (see event_detection.hpp).
#include "fremond/simulation/event_detection.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "simulation/detail/ulp.hpp"

namespace fremond {

namespace {

using detail::ulp;

// A lower bound of f on [0, h] from its values and slopes at both ends and |f''| ≤ C:
// f(s) ≥ p_a(s) = f_a + d_a s − C s²/2 and f(s) ≥ p_b(s) = f_b − d_b (h − s) − C (h − s)²/2.
// The minimum over [0, h] of max(p_a, p_b) sits at an end or where they cross (p_a − p_b is
// affine in s, so there is at most one crossing).
double pair_lower_bound(double fa, double da, double fb, double db, double C, double h) {
  const auto pa = [&](double s) { return fa + da * s - 0.5 * C * s * s; };
  const auto pb = [&](double s) {
    const double u = h - s;
    return fb - db * u - 0.5 * C * u * u;
  };
  double lb = std::min(std::max(pa(0.0), pb(0.0)), std::max(pa(h), pb(h)));
  const double c0 = fa - fb + db * h + 0.5 * C * h * h;
  const double c1 = da - db - C * h;
  if (c1 != 0.0) {
    const double s = -c0 / c1;
    if (s > 0.0 && s < h) lb = std::min(lb, std::max(pa(s), pb(s)));
  }
  return lb;
}

struct Point {
  double s, g, gd, gdd;
};

Point sample(const GapFunction& f, double s, long& evaluations) {
  Point p{s, 0.0, 0.0, 0.0};
  f.eval(s, p.g, p.gd, p.gdd);
  ++evaluations;
  return p;
}

// The smallest interval the search splits: a few units in the last place of its end, and never
// below 2⁻²⁰⁰ of the whole search (which bounds the depth of the splitting by 200 levels).
double min_width(double b, double floor) {
  return std::max(4.0 * ulp(b), floor);
}

// The single root of a decreasing g on [lo, hi] with g(lo) > 0 ≥ g(hi): Newton from the last
// point, kept inside the bracket, bisection when it leaves it. Returns the left-most point found
// with g ≤ 0, within a few units in the last place of the true crossing.
//
// Both Newton on a concave gap from the right and bisection from lo = 0 can do no better than
// halve hi: a root 1e-150 s into a 0.5 s search (g = 1e300 m/s²) takes about 500 halvings. The
// iteration bound covers the whole exponent range of a double (2⁻¹⁰⁷⁴ of s_max), so that the
// bound never decides where an event is; the width test ends every ordinary search long before.
double refine(const GapFunction& f, Point lo, Point hi, long& evaluations) {
  const auto min_width = [](double x) { return 4.0 * ulp(x); };
  Point last = hi;
  for (int it = 0; it < 1100; ++it) {
    if (hi.s - lo.s <= min_width(hi.s)) break;
    double x = last.gd < 0.0 ? last.s - last.g / last.gd : 0.5 * (lo.s + hi.s);
    if (!(x > lo.s && x < hi.s)) x = lo.s + 0.5 * (hi.s - lo.s);
    // A Newton step that no longer moves: close the bracket around x to one unit of rounding.
    if (std::fabs(x - last.s) <= min_width(x)) {
      const Point p = sample(f, x, evaluations);
      if (p.g <= 0.0) {
        hi = p;
        const double left = std::max(lo.s, x - min_width(x));
        const Point q = sample(f, left, evaluations);
        if (q.g > 0.0)
          lo = q;
        else
          hi = q;
      } else {
        lo = p;
        const double right = std::min(hi.s, x + min_width(x));
        const Point q = sample(f, right, evaluations);
        if (q.g <= 0.0)
          hi = q;
        else
          lo = q;
      }
      last = hi;
      continue;
    }
    const Point p = sample(f, x, evaluations);
    if (p.g <= 0.0)
      hi = p;
    else
      lo = p;
    last = p;
    if (p.g == 0.0) break;
  }
  return hi.s;
}

}  // namespace

EventSearchResult find_first_event(const GapFunction& f, double s_max, bool touching_start,
                                   long max_evaluations) {
  EventSearchResult out;
  if (!(s_max >= 0.0)) return out;
  Point start = sample(f, 0.0, out.evaluations);
  if (touching_start)
    start.gd = std::max(start.gd, 0.0);
  else if (start.g <= 0.0 && start.gd < 0.0) {  // already closed and closing: an event now
    out.s = 0.0;
    return out;
  }
  const Point end = sample(f, s_max, out.evaluations);

  // Left-first depth-first splitting; the right halves wait on a stack, one per level, and there
  // are at most 200 levels (min_width).
  struct Node {
    Point a, b;
  };
  const double floor = std::ldexp(s_max, -200);
  std::array<Node, 256> stack;
  int top = 0;
  stack[top++] = {start, end};
  while (top > 0) {
    const Node node = stack[--top];
    const Point& a = node.a;
    const Point& b = node.b;
    const double h = b.s - a.s;
    // g non-decreasing on [a, b]: no event (an event needs g ≤ 0 while decreasing, and g ≥ g(a)).
    if (pair_lower_bound(a.gd, a.gdd, b.gd, b.gdd, f.L, h) >= 0.0) continue;
    // g bounded away from zero on [a, b].
    if (pair_lower_bound(a.g, a.gd, b.g, b.gd, f.K, h) > 0.0) continue;
    // g decreasing on [a, b]: at most one crossing, at the first point where g ≤ 0.
    if (-pair_lower_bound(-a.gd, -a.gdd, -b.gd, -b.gdd, f.L, h) < 0.0) {
      if (b.g > 0.0) continue;
      out.s = a.g <= 0.0 ? a.s : refine(f, a, b, out.evaluations);
      return out;
    }
    if (h <= min_width(b.s, floor)) {
      if (b.g <= 0.0) {
        // At the depth bound (2⁻²⁰⁰ s_max) the crossing can still be far inside [a, b] when the
        // scene's time scale is that much below s_max (g = 1e200 m/s²): close in on it, not on
        // b. From a start that touches (g(a) ≤ 0, lifting off), first halve towards a for a
        // point still in flight, g > 0; the crossing is after it.
        Point lo = a, hi = b;
        while (lo.g <= 0.0 && hi.s - a.s > min_width(hi.s, 0.0)) {
          const Point m = sample(f, a.s + 0.5 * (hi.s - a.s), out.evaluations);
          (m.g > 0.0 ? lo : hi) = m;
        }
        out.s = lo.g <= 0.0 ? b.s : refine(f, lo, hi, out.evaluations);
        return out;
      }
      continue;  // a dip below zero of at most K h²/8, below the rounding of positions
    }
    // The refinement above is bounded (at most about 3,300 evaluations) and always finishes: a root
    // proven is never thrown away for the budget. Only the splitting is cut.
    if (out.evaluations >= max_evaluations) {
      out.exhausted = true;
      return out;
    }
    const Point m = sample(f, a.s + 0.5 * h, out.evaluations);
    if (top + 2 > static_cast<int>(stack.size())) break;  // cannot happen (see above)
    stack[top++] = {m, b};
    stack[top++] = {a, m};
  }
  return out;
}

}  // namespace fremond
