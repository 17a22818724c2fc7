#pragma once
/// @file A problem and its law as an impact-problem file (docs/problem-file.md), every number to 17
/// digits: the reproducer a stress failure prints, runnable as `fremond impact FILE`.
#include <sstream>
#include <string>

#include "fremond/fremond.hpp"

namespace fremond::robust {

namespace detail {

inline std::string json_number(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

template <class Derived>
std::string json_matrix(const Eigen::MatrixBase<Derived>& m) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    s += i ? ", [" : "[";
    for (Eigen::Index j = 0; j < m.cols(); ++j) s += (j ? ", " : "") + json_number(m(i, j));
    s += "]";
  }
  return s + "]";
}

template <class Derived>
std::string json_vector(const Eigen::MatrixBase<Derived>& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + json_number(v(i));
  return s + "]";
}

inline std::string json_per_contact(const PerContact& p) {
  if (p.values.size() == 1) return json_number(p.values[0]);
  std::string s = "[";
  for (std::size_t i = 0; i < p.values.size(); ++i) s += (i ? ", " : "") + json_number(p.values[i]);
  return s + "]";
}

/// One built-in potential per contact as {"potential": ..., "k": [...], ...}; a kind the file
/// cannot name is written with its description, so the reproducer at least says what it was.
inline std::string json_potentials(const PerContactPotential& ps) {
  const auto* p0 = ps.potentials.front().get();
  auto list = [&](auto get) {
    if (ps.potentials.size() == 1) return json_number(get(*ps.potentials.front()));
    std::string s = "[";
    for (std::size_t i = 0; i < ps.potentials.size(); ++i)
      s += (i ? ", " : "") + json_number(get(*ps.potentials[i]));
    return s + "]";
  };
  bool all_power = true, all_deadzone = true, all_abs = true;
  for (const auto& p : ps.potentials) {
    all_power = all_power && dynamic_cast<const PowerPotential*>(p.get());
    all_deadzone = all_deadzone && dynamic_cast<const DeadZonePowerPotential*>(p.get());
    all_abs = all_abs && dynamic_cast<const AbsoluteValuePotential*>(p.get());
  }
  if (all_power)
    return R"({"potential": "power", "k": )" +
           list([](const Potential& p) { return static_cast<const PowerPotential&>(p).k(); }) +
           ", \"p\": " +
           list([](const Potential& p) { return static_cast<const PowerPotential&>(p).p(); }) + "}";
  if (all_deadzone)
    return R"({"potential": "deadzone_power", "k": )" + list([](const Potential& p) {
             return static_cast<const DeadZonePowerPotential&>(p).k();
           }) +
           ", \"q\": " + list([](const Potential& p) {
             return static_cast<const DeadZonePowerPotential&>(p).q();
           }) +
           ", \"r\": " + list([](const Potential& p) {
             return static_cast<const DeadZonePowerPotential&>(p).r();
           }) +
           "}";
  if (all_abs)
    return R"({"potential": "absolute_value", "b": )" + list([](const Potential& p) {
             return static_cast<const AbsoluteValuePotential&>(p).bound();
           }) +
           "}";
  return "{\"potential\": \"" + std::string(p0->name()) + "\", \"described_as\": \"" +
         p0->describe() + "\"}";
}

}  // namespace detail

inline std::string law_to_json(const ImpactLaw& law) {
  using namespace detail;
  std::string s = "{\"type\": \"" + std::string(law.name()) + "\"";
  if (const auto* r = law.get_if<RestitutionLaw>()) {
    s += ", \"e\": " + json_per_contact(r->e);
    if (r->coulomb) s += ", \"mu\": " + json_per_contact(r->mu);
    return s + "}";
  }
  const FremondLaw& f = law.get<FremondLaw>();
  s += ", \"normal\": " + json_potentials(f.normal);
  if (f.tangential == TangentialLaw::potential)
    s += ", \"tangential\": " + json_potentials(f.tangential_potential);
  if (f.tangential == TangentialLaw::coulomb)
    s += ", \"tangential\": {\"potential\": \"coulomb\", \"mu\": " + json_per_contact(f.mu) + "}";
  return s + "}";
}

template <int N, int C>
std::string problem_to_json(const ImpactProblemT<N, C>& pb, const ImpactLaw& law) {
  using namespace detail;
  std::string s = "{\"M\": " + json_matrix(pb.M) + ",\n \"W_N\": " + json_matrix(pb.W_N);
  if (pb.has_tangential()) s += ",\n \"W_T\": " + json_matrix(pb.W_T);
  if (pb.w_N.size()) s += ",\n \"w_N\": " + json_vector(pb.w_N);
  if (pb.w_T.size() && pb.has_tangential()) s += ",\n \"w_T\": " + json_vector(pb.w_T);
  s += ",\n \"qdot_A\": " + json_vector(pb.qdot_A);
  return s + ",\n \"law\": " + law_to_json(law) + "}";
}

}  // namespace fremond::robust
