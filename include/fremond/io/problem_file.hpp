#pragma once
/// @file The impact-problem file (docs/problem-file.md): one problem and its law as a JSON object,
/// and the JSON form of a result.
///
/// The reader refuses anything that is not a valid problem, never filling in a default the file
/// did not ask for: bad JSON, keys docs/problem-file.md does not list, missing required keys, wrong
/// sizes, a mass matrix that is not symmetric positive definite, numbers that are not finite,
/// parameters out of range, unknown law types or potentials. Each refusal is an InvalidArgument
/// whose name() is the key as the file spells it (`M`, `W_N[2]`, `law.e`, `law.normal.p[1]`, ...).
///
/// Potentials are made by name through a PotentialRegistry passed by the caller (no global state),
/// so a user's own kinds can be used from a file:
///
///     auto registry = fremond::PotentialRegistry::with_builtins();
///     registry.add("my_law", {{"k"}, {}, make_my_law, "..."});
///     auto file = fremond::io::parse_problem_file(text, registry);
///     auto result = fremond::solve_impact(file.problem, file.law);
///     std::cout << fremond::io::result_to_json(result, 2);
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "fremond/core/impact_problem.hpp"
#include "fremond/laws/impact_law.hpp"
#include "fremond/potentials/registry.hpp"
#include "fremond/solvers/impact_result.hpp"
#include "fremond/sparse/sparse_problem.hpp"

namespace fremond::io {

/// What one impact-problem file holds.
struct ProblemFile {
  ImpactProblem problem;  ///< validated (validate(problem) holds); w_N, w_T are zero if not given.
  ImpactLaw law;          ///< validated for problem.contacts().
};

/// Reads an impact-problem file from its text. Keys (docs/problem-file.md): `M` (n×n), `W_N` (n×c),
/// `qdot_A` (n) and `law` are required; `W_T` (n×c; without it the problem is frictionless and P_T
/// = 0), `w_N`, `w_T` (c; zero when absent) are optional. Matrices are lists of rows, or sparse
/// (`{"rows": m, "cols": n, "triplets": [[i, j, value], ...]}`). Throws InvalidArgument naming the
/// key and the reason; a message without a key (empty input, a document that is not an object) is
/// named "problem".
ProblemFile parse_problem_file(std::string_view json_text, const PotentialRegistry& registry);

/// What one impact-problem file holds, stored sparse (docs/sparse.md).
struct SparseProblemFile {
  SparseImpactProblem problem;  ///< validated; w_N, w_T are zero if not given.
  ImpactLaw law;                ///< validated for problem.contacts().
};

/// The same file read into sparse storage, each matrix in either form, with the same checks and
/// messages.
SparseProblemFile parse_sparse_problem_file(std::string_view json_text,
                                            const PotentialRegistry& registry);

/// True when the file writes M, W_N or W_T in the sparse form: `fremond impact` then reads it with
/// parse_sparse_problem_file and solves it sparse where the law allows (docs/sparse.md). False for
/// text that is not a JSON object (the readers say what is wrong with it).
bool writes_sparse_matrices(std::string_view json_text);

/// Reads a law alone, the `law` object of the problem file (e.g. `{"type": "stronge_coulomb", "e":
/// 0.9, "mu": 1}`), validated for `contacts` contacts: any law of law_list.hpp by its name.
/// Throws InvalidArgument naming the key as `law.<key>`.
ImpactLaw parse_law(std::string_view json_text, int contacts, const PotentialRegistry& registry);

/// The same, reading the whole stream first.
ProblemFile read_problem_file(std::istream& in, const PotentialRegistry& registry);

/// One result as a JSON object: the keys of docs/problem-file.md (qdot_E, P_N, P_T, D_NA, D_TA,
/// D_NE, D_TE, energy_change, admissibility, unique, solver) plus P_N_reaction, takes_part,
/// solutions_found, Poisson's compression phase (P_NC, P_TC, D_NC, D_TC) when the result has it,
/// every field of the admissibility report and of the solver report. Doubles are printed so that
/// they read back to the same double; a number that is not finite (e.g. the residual of a solve
/// that did not run) is printed as null, so the output is always valid JSON. `indent` < 0 prints
/// one line; otherwise that many spaces per level.
template <int MaxDofs, int MaxContacts>
std::string result_to_json(const ImpactResultT<MaxDofs, MaxContacts>& result, int indent = -1);

/// Every solution of `fremond impact --all-solutions`: {"count": N, "solutions": [result, ...]}.
/// An empty list (count 0) means the law has no solution for these data.
std::string solutions_to_json(const std::vector<ImpactResult>& solutions, int indent = -1);

}  // namespace fremond::io
