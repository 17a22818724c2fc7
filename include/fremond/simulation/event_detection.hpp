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
///
/// The search has a budget of evaluations: a flight whose gap turns faster than it can be
/// resolved (a body spinning at 1e60 rad/s has 1e60 dips to rule out) ends the search with
/// `exhausted` instead of running for ever. Nothing is guessed then: the caller must stop.
#include <limits>

#include "fremond/simulation/free_flight.hpp"

namespace fremond {

/// Where a search ended.
struct EventSearchResult {
  /// Elapsed time of the first event in [0, s_max], +∞ when there is none.
  double s = std::numeric_limits<double>::infinity();
  long evaluations = 0;    ///< evaluations of (g, g', g'').
  bool exhausted = false;  ///< the budget ran out first: s is +∞ and means nothing.
  bool found() const { return s != std::numeric_limits<double>::infinity(); }
};

/// The default budget of one search: about 0.2 s of evaluations (about 85 ns each). A flight of
/// the paper's bar takes about 30; a body making 10⁵ turns in one flight, a few 10⁵.
inline constexpr long kDefaultEventSearchBudget = 2'000'000;

/// The first event of `gap` in [0, s_max]. With `touching_start` the contact is known to be in
/// contact at s = 0 and not approaching (it has just left an impact): its g'(0) is read as
/// max(g'(0), 0), so that rounding noise of the impact cannot raise a spurious event at s = 0
/// (the sign of the velocity decides, not a nudge of time). The splitting stops, `exhausted`, once
/// `max_evaluations` evaluations are spent.
EventSearchResult find_first_event(const GapFunction& gap, double s_max, bool touching_start,
                                   long max_evaluations = kDefaultEventSearchBudget);

}  // namespace fremond
