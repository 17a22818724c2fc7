// The impact-problem file of docs/problem-file.md: reader and result writer.
#include "fremond/io/problem_file.hpp"

#include <algorithm>

#include <cmath>
#include <istream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "fremond/core/error.hpp"
#include "fremond/core/types.hpp"
#include "io/detail/json_law.hpp"
#include "io/detail/json_number.hpp"
#include "io/detail/json_reader.hpp"

namespace fremond::io {

namespace {

using detail::json;

std::string dims(Eigen::Index r, Eigen::Index c) {
  return std::to_string(r) + "x" + std::to_string(c);
}

// validate(problem) takes an empty w_N, w_T or W_T as "not given"; in a file the key itself says
// whether it was given, so a present key of the wrong size is refused rather than read as absent.
// W_T is checked against W_N before validate() (which would otherwise blame w_T for a W_T given
// empty), but only once W_N has the rows of M, so that the first message names the first mistake.
template <class Problem>
void check_given_W_T(const Problem& pb, const json& doc) {
  const auto n = pb.W_N.rows(), c = pb.W_N.cols();
  if (doc.contains("W_T") && n == pb.M.rows() && (pb.W_T.rows() != n || pb.W_T.cols() != c))
    throw InvalidArgument(
        "W_T", "must be " + dims(n, c) + " like W_N, got " + dims(pb.W_T.rows(), pb.W_T.cols()));
}
template <class Problem>
void check_given_w(const Problem& pb, const json& doc) {
  const auto c = pb.W_N.cols();
  for (const char* key : {"w_N", "w_T"}) {
    const auto size = std::string(key) == "w_N" ? pb.w_N.size() : pb.w_T.size();
    if (doc.contains(key) && size != c)
      throw InvalidArgument(key, "must have " + std::to_string(c) +
                                     " entries (one per contact), got " + std::to_string(size));
  }
}

}  // namespace

ImpactLaw parse_law(std::string_view json_text, int contacts, const PotentialRegistry& registry) {
  if (contacts < 1)
    throw InvalidArgument("contacts", "must be >= 1, got " + std::to_string(contacts));
  return detail::law_from_json(detail::parse_json(json_text, "law"), contacts, registry, "law");
}

namespace {

// The document, its keys checked: unknown keys before anything else, so that a misspelt optional
// key (say "w_n") does not leave its default in place silently (docs/problem-file.md).
json problem_document(std::string_view json_text) {
  json doc = detail::parse_json(json_text, "problem");
  detail::require_object(doc, "problem");
  detail::check_keys(doc, "", {"M", "W_N", "W_T", "w_N", "w_T", "qdot_A", "law"},
                     "the impact-problem file");
  for (const char* key : {"M", "W_N", "qdot_A", "law"}) detail::required_key(doc, "", key);
  return doc;
}

// The members of a dense or a sparse problem, `matrix` reading each matrix; validated, with the
// obstacles' terms stored (zero when absent) so that every user of the problem sees c entries.
template <class Problem, class ReadMatrix>
void read_members(const json& doc, Problem& pb, ReadMatrix matrix) {
  pb.M = matrix(doc["M"], "M");
  pb.W_N = matrix(doc["W_N"], "W_N");
  if (const json* j = detail::optional_key(doc, "W_T"))
    pb.W_T = matrix(*j, "W_T");
  else
    pb.W_T.resize(pb.W_N.rows(), 0);  // frictionless: no tangential rows (docs/problem-file.md)
  if (const json* j = detail::optional_key(doc, "w_N"))
    pb.w_N = detail::vector_from_json(*j, "w_N");
  if (const json* j = detail::optional_key(doc, "w_T"))
    pb.w_T = detail::vector_from_json(*j, "w_T");
  pb.qdot_A = detail::vector_from_json(doc["qdot_A"], "qdot_A");
  check_given_W_T(pb, doc);
  validate(pb);  // sizes, symmetry, positive definiteness; messages name M, W_N, ...
  check_given_w(pb, doc);
  // Fixed obstacles by default (docs/concepts.md: w_N, w_T are zero for a fixed obstacle).
  if (pb.w_N.size() == 0) pb.w_N.setZero(pb.W_N.cols());
  if (pb.w_T.size() == 0 && pb.has_tangential()) pb.w_T.setZero(pb.W_N.cols());
}

}  // namespace

ProblemFile parse_problem_file(std::string_view json_text, const PotentialRegistry& registry) {
  const json doc = problem_document(json_text);
  ProblemFile out;
  read_members(doc, out.problem, detail::matrix_from_json);
  out.law = detail::law_from_json(doc["law"], out.problem.contacts(), registry, "law");
  return out;
}

SparseProblemFile parse_sparse_problem_file(std::string_view json_text,
                                            const PotentialRegistry& registry) {
  const json doc = problem_document(json_text);
  SparseProblemFile out;
  read_members(doc, out.problem, detail::sparse_matrix_from_json);
  out.law = detail::law_from_json(doc["law"], out.problem.contacts(), registry, "law");
  return out;
}

bool writes_sparse_matrices(std::string_view json_text) {
  json doc;
  try {
    doc = detail::parse_json(json_text, "problem");
  } catch (const InvalidArgument&) {
    return false;
  }
  if (!doc.is_object()) return false;
  for (const char* key : {"M", "W_N", "W_T"})
    if (const json* j = detail::optional_key(doc, key); j && detail::is_sparse_matrix_json(*j))
      return true;
  return false;
}

ProblemFile read_problem_file(std::istream& in, const PotentialRegistry& registry) {
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InvalidArgument("problem", "could not read the input");
  return parse_problem_file(text, registry);
}

namespace {

using ojson = nlohmann::ordered_json;  // keeps the order of docs/problem-file.md in the output

using detail::json_number;

template <class Derived>
ojson numbers(const Eigen::MatrixBase<Derived>& v) {
  ojson a = ojson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(json_number(static_cast<double>(v(i))));
  return a;
}

template <class Derived>
ojson flags(const Eigen::MatrixBase<Derived>& v) {
  ojson a = ojson::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v(i) != 0);
  return a;
}

template <int C>
ojson admissibility_json(const AdmissibilityReportT<C>& a) {
  ojson j;
  j["total"] = json_number(a.total);
  j["per_contact"] = numbers(a.per_contact);
  j["reaction"] = json_number(a.reaction);
  j["dissipation"] = json_number(a.dissipation);
  j["complementarity"] = json_number(a.complementarity);
  j["penetration"] = json_number(a.penetration);
  j["fenchel_young_gap"] = json_number(a.fenchel_young_gap);
  j["tolerance"] = json_number(a.tolerance);
  j["admissible"] = a.admissible;
  j["failed"] = std::string(to_string(a.failed));
  j["failed_contact"] = a.failed_contact;
  j["violation"] = json_number(a.violation);
  j["energy_change"] = json_number(a.energy_change);
  j["kinetic_energy_A"] = json_number(a.kinetic_energy_A);
  return j;
}

ojson solver_json(const SolverReport& s) {
  ojson j;
  j["method"] = std::string(to_string(s.method));
  j["status"] = std::string(to_string(s.status));
  j["criterion"] = std::string(to_string(s.criterion));
  j["iterations"] = s.iterations;
  j["residual"] = json_number(s.residual);
  j["message"] = std::string(s.message);
  j["native_code"] = s.native_code;
  j["fallbacks"] = s.fallbacks;
  ojson attempts = ojson::array();
  for (int i = 0; i < std::min(s.attempt_count, SolverReport::kMaxAttempts); ++i) {
    const Attempt& a = s.attempts[static_cast<std::size_t>(i)];
    ojson one;
    one["method"] = std::string(to_string(a.method));
    one["start"] = std::string(to_string(a.start));
    one["status"] = std::string(to_string(a.status));
    one["residual"] = json_number(a.residual);
    attempts.push_back(one);
  }
  j["attempts"] = attempts;
  j["attempt_count"] = s.attempt_count;
  return j;
}

template <int N, int C>
ojson result_json(const ImpactResultT<N, C>& r) {
  ojson j;
  j["qdot_E"] = numbers(r.qdot_E);
  j["P_N"] = numbers(r.P_N);
  j["P_T"] = numbers(r.P_T);
  j["D_NA"] = numbers(r.D_NA);
  j["D_TA"] = numbers(r.D_TA);
  j["D_NE"] = numbers(r.D_NE);
  j["D_TE"] = numbers(r.D_TE);
  // The reaction part is Frémond's; for the other laws it is zero (impact_result.hpp), which a
  // solver may leave unsized: print the zeros, so that every per-contact list has c entries.
  if (r.P_N_reaction.size() == 0 && r.P_N.size() != 0)
    j["P_N_reaction"] = numbers(Eigen::VectorXd::Zero(r.P_N.size()));
  else
    j["P_N_reaction"] = numbers(r.P_N_reaction);
  j["takes_part"] = flags(r.takes_part);
  j["energy_change"] = json_number(r.energy_change);
  if (r.has_phases) {  // Poisson: the end of compression (docs/laws.md)
    j["P_NC"] = numbers(r.P_NC);
    j["P_TC"] = numbers(r.P_TC);
    j["D_NC"] = numbers(r.D_NC);
    j["D_TC"] = numbers(r.D_TC);
    j["qdot_C"] = numbers(r.qdot_C);
  }
  j["unique"] = r.unique;
  // 0 means "not counted" (uniqueness decided without listing the solutions): null, so that it
  // does not read as "no solution" beside "unique": true.
  if (r.solutions_found > 0)
    j["solutions_found"] = r.solutions_found;
  else
    j["solutions_found"] = nullptr;
  j["admissibility"] = admissibility_json(r.admissibility);
  j["solver"] = solver_json(r.solver);
  return j;
}

// Invalid UTF-8 can only come from a user's potential name or message; replace it rather than
// throw while printing a result.
std::string dump(const ojson& j, int indent) {
  return j.dump(indent < 0 ? -1 : indent, ' ', false, ojson::error_handler_t::replace);
}

}  // namespace

template <int N, int C>
std::string result_to_json(const ImpactResultT<N, C>& result, int indent) {
  return dump(result_json(result), indent);
}

template std::string result_to_json(const ImpactResultT<Dynamic, Dynamic>&, int);
template std::string result_to_json(const ImpactResultT<kSmallDofs, kSmallContacts>&, int);

std::string solutions_to_json(const std::vector<ImpactResult>& solutions, int indent) {
  ojson j;
  j["count"] = solutions.size();
  j["solutions"] = ojson::array();
  for (const auto& r : solutions) j["solutions"].push_back(result_json(r));
  return dump(j, indent);
}

}  // namespace fremond::io
