// The law atlas (include/fremond/atlas/atlas.hpp) as a dict of NumPy arrays: the arrays of the
// command's .npz (io::atlas_arrays), so the two cannot drift apart. The sweep runs with the
// interpreter's lock released.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>

#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "fremond/atlas/atlas.hpp"
#include "fremond/io/atlas_file.hpp"
#include "fremond/scenes/presets.hpp"
#include "python/bind_helpers.hpp"

namespace fremond::python {

namespace {

// One array as NumPy's, copied from its bytes; a 0-d array as a Python scalar.
py::object to_numpy(const io::NpyArray& a) {
  std::vector<py::ssize_t> shape(a.shape.begin(), a.shape.end());
  py::array out(py::dtype(a.descr), shape);
  std::memcpy(out.mutable_data(), a.bytes.data(), a.bytes.size());
  if (a.shape.empty()) return out.attr("item")();
  return out;
}

py::dict atlas(const std::optional<Scene>& scene, const std::vector<std::string>& laws,
               const std::string& reference, const std::string& parameter,
               const std::vector<double>& values, double e, double mu, double fremond_p,
               double fremond_k_N, int contact, int theta_count, double theta_min, double theta_max,
               int psi_count, double psi_min, double psi_max, const std::vector<double>& spins,
               double speed, int threads, const SolverOptions& solver,
               const std::optional<py::function>& progress) {
  AtlasOptions o;
  o.laws = laws;
  o.reference = reference;
  o.parameter = atlas_parameter_from_string(parameter);
  o.values = values;
  o.e = e;
  o.mu = mu;
  o.fremond_p = fremond_p;
  o.fremond_k_N = fremond_k_N;
  o.contact = contact;
  o.theta_count = theta_count;
  o.theta_min = theta_min;
  o.theta_max = theta_max;
  o.psi_count = psi_count;
  o.psi_min = psi_min;
  o.psi_max = psi_max;
  o.spins = spins;
  o.speed = speed;
  o.threads = threads;
  o.solver = solver;
  if (progress) {
    // Called between blocks on this thread, which gave the lock up: take it back for the call.
    o.progress = [f = *progress](std::size_t done, std::size_t total) {
      py::gil_scoped_acquire lock;
      f(done, total);
    };
  }
  const Scene s = scene ? *scene : bar_scene(BarParameters{}, ImpactLaw::newton(0.9));
  std::vector<io::NpyArray> arrays;
  {
    py::gil_scoped_release release;
    arrays = io::atlas_arrays(law_atlas(s, o));
  }
  py::dict d;
  for (const io::NpyArray& a : arrays) d[py::str(a.name)] = to_numpy(a);
  return d;
}

}  // namespace

void bind_atlas(py::module_& m) {
  const AtlasOptions defaults;
  m.def("atlas", &atlas, py::arg("scene") = py::none(), py::arg("laws") = defaults.laws,
        py::arg("reference") = "", py::arg("parameter") = "mu", py::arg("values") = defaults.values,
        py::arg("e") = defaults.e, py::arg("mu") = defaults.mu,
        py::arg("fremond_p") = defaults.fremond_p, py::arg("fremond_k_N") = defaults.fremond_k_N,
        py::arg("contact") = defaults.contact, py::arg("theta_count") = defaults.theta_count,
        py::arg("theta_min") = defaults.theta_min, py::arg("theta_max") = defaults.theta_max,
        py::arg("psi_count") = defaults.psi_count, py::arg("psi_min") = defaults.psi_min,
        py::arg("psi_max") = defaults.psi_max, py::arg("spins") = defaults.spins,
        py::arg("speed") = defaults.speed, py::arg("threads") = defaults.threads,
        py::arg("options") = SolverOptions{}, py::arg("progress") = py::none(),
        R"(The law atlas of a scene (docs/atlas.md): one contact swept over the body's angle theta,
the direction psi of the contact velocity before the impact ((D_TA, D_NA) = speed (cos psi,
sin psi), psi in [-pi, 0]) and the spin ratios, under each law of `laws` and each value of the
swept `parameter` ("mu" or "e"; the other is fixed by `mu` or `e`). scene=None: the paper's bar.
Frémond's k_N (fremond_k_N=0) is calibrated to e at the scene's first impact; contact=-1 and
speed=0 take the first impact's contact and speed.

Returns a dict of NumPy arrays, the same as `fremond atlas --npz`: axes (laws, values, spins,
theta, psi) and scalars (parameter, reference, e, mu, speed, contact, ...); per configuration,
shape (spins, theta, psi): D_NA, D_TA, kinetic_energy, qdot_A (..., 3); per point, shape (laws,
values, spins, theta, psi): energy_ratio, distance, P_N, P_T, D_NE, D_TE, qdot_E (..., 3), and the
codes admissible, failed, status, mode, solutions, with failed_names, status_names, mode_names.
The interpreter's lock is released during the sweep; `progress(done, total)` is called between
blocks. A bad value raises ValueError naming it.)");
}

}  // namespace fremond::python
