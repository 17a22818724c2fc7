#pragma once
/// @file Finding the first contact event of a free flight, with no event ever missed.
///
/// An event of a contact is an instant where its gap g reaches zero from above (or is ≤ 0 while
/// decreasing). The search never samples on a fixed grid: it splits [0, s_max] left first and
/// discards an interval only when a bound proves it holds no event,
///   - g is non-decreasing on it: the lower bound of g' from both ends with |g'''| ≤ L is ≥ 0;
///   - g stays positive on it: the lower bound of g from both ends with |g''| ≤ K is > 0;
///   - g is decreasing on it and ends positive;
/// and refines (safeguarded Newton, to the last bits) only an interval where g is proven
/// decreasing and changes sign, which then holds exactly one root. A grazing touch that dips below
/// zero by less than K h²/8 on an interval of the smallest representable width h is not an event
/// (the dip is below the rounding of positions); one that crosses is found however brief.
#include <limits>

#include "fremond/simulation/free_flight.hpp"

namespace fremond {

/// Where a search ended.
struct EventSearchResult {
  /// Elapsed time of the first event in [0, s_max], +∞ when there is none.
  double s = std::numeric_limits<double>::infinity();
  int evaluations = 0;  ///< evaluations of (g, g', g'').
  bool found() const { return s != std::numeric_limits<double>::infinity(); }
};

/// The first event of `gap` in [0, s_max]. With `touching_start` the contact is known to be in
/// contact at s = 0 and not approaching (it has just left an impact): its g'(0) is read as
/// max(g'(0), 0), so that rounding noise of the impact cannot raise a spurious event at s = 0
/// (the sign of the velocity decides, not a nudge of time).
EventSearchResult find_first_event(const GapFunction& gap, double s_max, bool touching_start);

}  // namespace fremond
