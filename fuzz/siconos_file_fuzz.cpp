// Fuzz target: the reader of Siconos's friction-contact files (docs/sparse.md), then the sparse
// solver on what it accepts, then the JSON writer.
//
// Contract checked on every input:
//  - the reader either accepts or throws InvalidArgument with a name and a reason; nothing else
//    escapes (any other exception, a crash, a sanitizer report or a hang is a finding);
//  - what it accepts validates again, with one μ ≥ 0 per contact;
//  - the sparse solve ends with a status, and a converged answer is finite, with P_N ≥ 0;
//  - the result prints as JSON that reads back.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string_view>

#include "fremond/io/problem_file.hpp"
#include "fremond/io/siconos_file.hpp"
#include "fremond/sparse/sparse_solver.hpp"
#include "fuzz_support.hpp"

using namespace fremond;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  io::SiconosProblem file;
  try {
    file = io::parse_siconos_file(text);
  } catch (const InvalidArgument& e) {
    fuzz::check_refusal(e);
    return 0;
  }
  const bool local = file.form == io::SiconosProblem::Form::local;
  try {
    if (local)
      validate(file.contact);
    else
      validate(file.impact);
  } catch (const InvalidArgument& e) {
    fuzz::fail(std::string("the reader accepted an invalid problem: ") + e.what());
  }
  if (static_cast<int>(file.mu.size()) !=
      (local ? file.contact.contacts() : file.impact.contacts()))
    fuzz::fail("the reader's mu does not have one value per contact");
  for (const double m : file.mu)
    if (!(m >= 0.0) || !std::isfinite(m)) fuzz::fail("the reader accepted a bad mu");
  // Keep every run short: the sweeps' cost grows with the size, which says nothing new here.
  if (file.contacts() > 16) return 0;
  const SparseSolverOptions options{.tolerance = 1e-10, .max_sweeps = 2000};
  ImpactResult r;
  try {
    r = local ? solve_contact_problem(file.contact, file.law(), options)
              : solve_impact(file.impact, file.law(), options);
  } catch (const InvalidArgument& e) {  // data whose G or velocities overflow
    fuzz::check_refusal(e);
    return 0;
  }
  if (r.solver.status == SolverStatus::not_run)
    fuzz::fail("the sparse solve did not say how it ended");
  if (r.ok()) {
    if (!r.P_N.allFinite() || !r.P_T.allFinite() || !r.D_NE.allFinite())
      fuzz::fail("a converged sparse answer is not finite");
    if (r.P_N.size() > 0 && r.P_N.minCoeff() < 0.0) fuzz::fail("a converged answer has P_N < 0");
  }
  const std::string json = io::result_to_json(r, -1);
  if (!nlohmann::json::accept(json)) fuzz::fail("result_to_json printed invalid JSON: " + json);
  return 0;
}
