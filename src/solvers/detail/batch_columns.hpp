#pragma once
/// @file One answer written into its column of a BatchAnswers (docs/solvers.md#batches), by the
/// prepared solver's solve_into(qdot_A, answers, column) and so by solve_batch.
#include <algorithm>
#include <limits>

#include "fremond/solvers/batch_answers.hpp"
#include "fremond/solvers/impact_result.hpp"

namespace fremond::detail {

/// Column k of `to` = from, where the answer has it; NaN where it has none (a method the law does
/// not support leaves the result's vectors empty). Entry by entry on the raw column: Eigen's
/// assignment of a block costs more than the bar's five copies of one to three numbers.
template <class From>
void put_column(Eigen::MatrixXd& to, Eigen::Index k, const From& from) {
  const Eigen::Index rows = to.rows();
  double* const col = to.data() + k * rows;
  if (from.size() == rows)
    for (Eigen::Index i = 0; i < rows; ++i) col[i] = from(i);
  else
    std::fill(col, col + rows, std::numeric_limits<double>::quiet_NaN());
}

/// Column k of `answers` from the answer `r`, with its certificate's verdict `admissible` (r's
/// own report where a whole solve made it).
template <int N, int C>
void put_answer(const ImpactResultT<N, C>& r, bool admissible, BatchAnswers& answers,
                Eigen::Index k) {
  put_column(answers.qdot_E, k, r.qdot_E);
  put_column(answers.P_N, k, r.P_N);
  put_column(answers.P_T, k, r.P_T);
  put_column(answers.D_NE, k, r.D_NE);
  put_column(answers.D_TE, k, r.D_TE);
  const auto i = static_cast<std::size_t>(k);
  answers.energy_change(k) = r.energy_change;
  answers.residual(k) = r.solver.residual;
  answers.status[i] = r.solver.status;
  answers.admissible[i] = admissible ? 1 : 0;
  answers.unique[i] = r.unique ? 1 : 0;
}

}  // namespace fremond::detail
