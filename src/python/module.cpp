// The compiled part of the Python package `fremond` (imported by fremond/__init__.py). It only
// wires up the binding units; each binds one layer of the library.
#include "python/bind_helpers.hpp"
#include "python/docstrings.hpp"

PYBIND11_MODULE(_fremond, m) {
  namespace fp = fremond::python;
  m.doc() = fp::doc::kModule;
  fp::bind_enums(m);
  fp::bind_potentials(m);
  fp::bind_impacts(m);
  fp::bind_scenes(m);
  fp::bind_simulation(m);
  fp::bind_multibody(m);  // after the simulation options it takes
  fp::bind_curves(m);
  fp::bind_batch(m);
  fp::bind_atlas(m);
  fp::bind_fit(m);
  fp::bind_sparse(m);
}
