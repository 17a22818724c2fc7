// The measured-impact file of docs/measurements.md.
#include "fremond/io/measurements.hpp"

#include <istream>
#include <iterator>
#include <limits>
#include <string>

#include "fremond/core/error.hpp"
#include "io/detail/json_reader.hpp"

namespace fremond::io {

namespace {

using detail::json;

std::string dims(Eigen::Index r, Eigen::Index c) {
  return std::to_string(r) + "x" + std::to_string(c);
}

// The library's validate() names members (`M`, `qdot_E[1]`); the file names them under the row.
InvalidArgument in_row(const InvalidArgument& e, const std::string& row) {
  const std::string what = e.what();
  return InvalidArgument(row + "." + e.name(), what.substr(e.name().size() + 2));
}

// qdot_E: n numbers, null where nothing was measured (NaN here, never read: the mask is false).
VectorX measured_values(const json& j, const std::string& key, std::vector<bool>& given) {
  if (!j.is_array())
    throw InvalidArgument(key, "must be a list of numbers (null where not measured), got " +
                                   detail::describe_json(j));
  VectorX v(static_cast<Eigen::Index>(j.size()));
  given.assign(j.size(), true);
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (j[i].is_null()) {
      v(static_cast<Eigen::Index>(i)) = std::numeric_limits<double>::quiet_NaN();
      given[i] = false;
    } else {
      v(static_cast<Eigen::Index>(i)) = detail::number_from_json(j[i], detail::index_path(key, i));
    }
  }
  return v;
}

std::vector<bool> mask_from_json(const json& j, const std::string& key) {
  if (!j.is_array())
    throw InvalidArgument(
        key, "must be a list of booleans (true: measured), got " + detail::describe_json(j));
  std::vector<bool> mask;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_boolean())
      throw InvalidArgument(detail::index_path(key, i),
                            "must be true or false, got " + detail::describe_json(j[i]));
    mask.push_back(j[i].get<bool>());
  }
  return mask;
}

MeasuredImpact read_row(const json& doc, const std::string& row) {
  detail::require_object(doc, row);
  // Unknown keys first: a misspelt optional key (say "Sigma") must not leave its default in place.
  detail::check_keys(doc, row,
                     {"M", "W_N", "W_T", "w_N", "w_T", "qdot_A", "qdot_E", "mask", "sigma"},
                     "a measured impact");
  for (const char* key : {"M", "W_N", "qdot_A", "qdot_E"}) detail::required_key(doc, row, key);
  const auto at = [&row](const char* key) { return detail::key_path(row, key); };

  MeasuredImpact m;
  ImpactProblem& pb = m.problem;
  pb.M = detail::matrix_from_json(doc["M"], at("M"));
  pb.W_N = detail::matrix_from_json(doc["W_N"], at("W_N"));
  if (const json* j = detail::optional_key(doc, "W_T"))
    pb.W_T = detail::matrix_from_json(*j, at("W_T"));
  else
    pb.W_T.resize(pb.W_N.rows(), 0);  // frictionless, as in the impact-problem file
  if (const json* j = detail::optional_key(doc, "w_N"))
    pb.w_N = detail::vector_from_json(*j, at("w_N"));
  if (const json* j = detail::optional_key(doc, "w_T"))
    pb.w_T = detail::vector_from_json(*j, at("w_T"));
  pb.qdot_A = detail::vector_from_json(doc["qdot_A"], at("qdot_A"));
  // A key given with the wrong size is refused, not read as absent (validate() takes an empty
  // W_T, w_N, w_T as "not given"), and W_T only once W_N has the rows of M: the first message
  // names the first mistake, as problem_file.cpp does.
  const auto n = pb.W_N.rows(), c = pb.W_N.cols();
  if (doc.contains("W_T") && n == pb.M.rows() && (pb.W_T.rows() != n || pb.W_T.cols() != c))
    throw InvalidArgument(at("W_T"), "must be " + dims(n, c) + " like W_N, got " +
                                         dims(pb.W_T.rows(), pb.W_T.cols()));
  try {
    validate(pb);
  } catch (const InvalidArgument& e) {
    throw in_row(e, row);
  }
  for (const char* key : {"w_N", "w_T"}) {
    const auto size = std::string(key) == "w_N" ? pb.w_N.size() : pb.w_T.size();
    if (doc.contains(key) && size != c)
      throw InvalidArgument(at(key), "must have " + std::to_string(c) +
                                         " entries (one per contact), got " + std::to_string(size));
  }
  if (pb.w_N.size() == 0) pb.w_N.setZero(c);
  if (pb.w_T.size() == 0 && pb.has_tangential()) pb.w_T.setZero(c);

  std::vector<bool> given;
  m.qdot_E = measured_values(doc["qdot_E"], at("qdot_E"), given);
  if (const json* j = detail::optional_key(doc, "mask")) {
    m.mask = mask_from_json(*j, at("mask"));
    // null says "not measured"; a mask that says "measured" there contradicts it.
    for (std::size_t i = 0; i < given.size() && i < m.mask.size(); ++i)
      if (m.mask[i] && !given[i])
        throw InvalidArgument(detail::index_path(at("qdot_E"), i),
                              "is null but mask[" + std::to_string(i) + "] says it was measured");
  } else {
    m.mask = given;
  }
  const auto dofs = pb.M.rows();
  m.sigma = VectorX::Ones(dofs);
  if (const json* j = detail::optional_key(doc, "sigma")) {
    if (j->is_number()) {
      m.sigma.setConstant(detail::number_from_json(*j, at("sigma")));
    } else {
      m.sigma = detail::vector_from_json(*j, at("sigma"));
    }
  }
  try {
    validate(m);
  } catch (const InvalidArgument& e) {
    throw in_row(e, row);
  }
  return m;
}

}  // namespace

std::vector<MeasuredImpact> parse_measurements(std::string_view json_text) {
  const json doc = detail::parse_json(json_text, "impacts");
  if (!doc.is_array())
    throw InvalidArgument("impacts",
                          "the measured-impact file must be a JSON array of impacts, "
                          "got " +
                              detail::describe_json(doc));
  if (doc.empty()) throw InvalidArgument("impacts", "holds no impact");
  std::vector<MeasuredImpact> out;
  out.reserve(doc.size());
  for (std::size_t i = 0; i < doc.size(); ++i)
    out.push_back(read_row(doc[i], detail::index_path("impacts", i)));
  return out;
}

std::vector<MeasuredImpact> read_measurements(std::istream& in) {
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InvalidArgument("impacts", "could not read the input");
  return parse_measurements(text);
}

}  // namespace fremond::io
