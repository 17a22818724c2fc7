// An atlas as NumPy arrays and as CSV (see atlas_file.hpp and docs/atlas.md).
#include "fremond/io/atlas_file.hpp"

#include <charconv>
#include <cmath>

#include "fremond/admissibility/admissibility_report.hpp"
#include "fremond/solvers/solver_status.hpp"

namespace fremond::io {

namespace {

// The names of codes 0, 1, ... of an enum, up to the first the enum does not name.
template <class E>
std::vector<std::string> code_names(int count) {
  std::vector<std::string> names;
  for (int i = 0; i < count; ++i) names.emplace_back(to_string(static_cast<E>(i)));
  return names;
}
constexpr int kInequalities = 8;    // none ... non_penetration
constexpr int kSolverStatuses = 7;  // not_run ... unsupported
constexpr int kAtlasModes = 4;      // stick ... unknown

// The shortest text that reads back to the same double (`nan` for NaN): a 400 x 400 map is
// millions of numbers, which %.17g writes several times slower and longer.
void number(std::string& out, double v) {
  char buf[32];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  out.append(buf, end);
}

}  // namespace

const char* const kAtlasCsvHeader =
    "law,mu,e,k_N,spin,theta,psi,D_NA,D_TA,T_A,energy_ratio,admissible,failed,solutions,mode,"
    "status,distance,P_N,P_T,D_NE,D_TE,xdot_E,ydot_E,thetadot_E";

std::vector<NpyArray> atlas_arrays(const AtlasResult& a) {
  const std::size_t nl = a.laws.size(), nv = a.values.size(), ns = a.spins.size(),
                    nt = a.theta.size(), np = a.psi.size();
  const std::vector<std::size_t> config{ns, nt, np}, point{nl, nv, ns, nt, np};
  std::vector<NpyArray> out;
  out.push_back(npy_array("laws", a.laws, {nl}));
  out.push_back(npy_array("reference", {a.reference}, {}));
  out.push_back(npy_array("parameter", {std::string(to_string(a.parameter))}, {}));
  out.push_back(npy_array("values", a.values, {nv}));
  out.push_back(npy_array("e", std::vector<double>{a.e}, {}));
  out.push_back(npy_array("mu", std::vector<double>{a.mu}, {}));
  out.push_back(npy_array("fremond_k_N", a.fremond_k_N, {nv}));
  out.push_back(npy_array("fremond_p", std::vector<double>{a.fremond_p}, {}));
  out.push_back(npy_array("spins", a.spins, {ns}));
  out.push_back(npy_array("theta", a.theta, {nt}));
  out.push_back(npy_array("psi", a.psi, {np}));
  out.push_back(npy_array("speed", std::vector<double>{a.speed}, {}));
  out.push_back(npy_array("contact", std::vector<std::int32_t>{a.contact}, {}));
  out.push_back(npy_array("radius_of_gyration", std::vector<double>{a.radius_of_gyration}, {}));
  out.push_back(npy_array("D_NA", a.D_NA, config));
  out.push_back(npy_array("D_TA", a.D_TA, config));
  out.push_back(npy_array("kinetic_energy", a.kinetic_energy, config));
  out.push_back(npy_array("qdot_A", a.qdot_A, {ns, nt, np, 3}));
  out.push_back(npy_array("energy_ratio", a.energy_ratio, point));
  out.push_back(npy_array("distance", a.distance, point));
  out.push_back(npy_array("P_N", a.P_N, point));
  out.push_back(npy_array("P_T", a.P_T, point));
  out.push_back(npy_array("D_NE", a.D_NE, point));
  out.push_back(npy_array("D_TE", a.D_TE, point));
  out.push_back(npy_array("qdot_E", a.qdot_E, {nl, nv, ns, nt, np, 3}));
  out.push_back(npy_array("admissible", a.admissible, point));
  out.push_back(npy_array("failed", a.failed, point));
  out.push_back(npy_array("status", a.status, point));
  out.push_back(npy_array("mode", a.mode, point));
  out.push_back(npy_array("solutions", a.solutions, point));
  out.push_back(npy_array("failed_names", code_names<Inequality>(kInequalities), {kInequalities}));
  out.push_back(
      npy_array("status_names", code_names<SolverStatus>(kSolverStatuses), {kSolverStatuses}));
  out.push_back(npy_array("mode_names", code_names<AtlasMode>(kAtlasModes), {kAtlasModes}));
  return out;
}

std::string atlas_npz(const AtlasResult& atlas) {
  return npz_archive(atlas_arrays(atlas));
}

std::string atlas_csv(const AtlasResult& a) {
  std::string out = std::string(kAtlasCsvHeader) + "\n";
  out.reserve(out.size() + a.points() * 400);
  const bool sweeps_e = a.parameter == AtlasParameter::e;
  for (std::size_t l = 0; l < a.laws.size(); ++l)
    for (std::size_t v = 0; v < a.values.size(); ++v) {
      // Every row gives μ, e and Frémond's k_N (nan for the other laws), whichever the law reads.
      std::string law = a.laws[l] + ",";
      number(law, sweeps_e ? a.mu : a.values[v]);
      law += ',';
      number(law, sweeps_e ? a.values[v] : a.e);
      law += ',';
      number(law, a.laws[l] == "fremond" ? a.fremond_k_N[v] : std::nan(""));
      for (std::size_t s = 0; s < a.spins.size(); ++s)
        for (std::size_t i = 0; i < a.theta.size(); ++i)
          for (std::size_t j = 0; j < a.psi.size(); ++j) {
            const std::size_t c = a.config(s, i, j), p = a.index(l, v, s, i, j);
            out += law;
            for (double x : {a.spins[s], a.theta[i], a.psi[j], a.D_NA[c], a.D_TA[c],
                             a.kinetic_energy[c], a.energy_ratio[p]}) {
              out += ',';
              number(out, x);
            }
            out += a.admissible[p] ? ",1," : ",0,";
            out += to_string(static_cast<Inequality>(a.failed[p]));
            out += ',' + std::to_string(a.solutions[p]) + ',';
            out += to_string(static_cast<AtlasMode>(a.mode[p]));
            out += ',';
            out += to_string(static_cast<SolverStatus>(a.status[p]));
            for (double x : {a.distance[p], a.P_N[p], a.P_T[p], a.D_NE[p], a.D_TE[p],
                             a.qdot_E[3 * p], a.qdot_E[3 * p + 1], a.qdot_E[3 * p + 2]}) {
              out += ',';
              number(out, x);
            }
            out += '\n';
          }
    }
  return out;
}

}  // namespace fremond::io
