#pragma once
/// @file A solver chain as a table (docs/solvers.md): an ordered list of stages, each a test of
/// where it applies and a run that answers (true) or hands on what it learned to the next.

namespace fremond::detail {

/// One row of a chain's table: where it applies, and what it runs (true: the answer is written).
/// A compile-time row, so that trying a stage costs the test itself.
template <auto Applies, auto Run>
struct Stage {
  template <class Chain>
  static bool answers(Chain& chain) {
    return (chain.*Applies)() && (chain.*Run)();
  }
};

/// Tries the stages in order; the first that answers ends the chain.
template <class... Stages, class Chain>
void run_stages(Chain& chain) {
  (void)(Stages::answers(chain) || ...);
}

}  // namespace fremond::detail
