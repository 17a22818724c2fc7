#pragma once
// The few helpers every binding file shares, so that each C++ concept is bound once and the same
// way: enums by their library names (to_string / from_string), option structs built from keyword
// arguments, and the binding units' entry points.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <initializer_list>
#include <string>
#include <string_view>

namespace fremond::python {

namespace py = pybind11;

/// Binds enum E under the names the library gives it (the problem file's and the command line's),
/// with str() giving that name, E.from_string(text), and a constructor from text so that a string
/// is accepted wherever the enum is.
template <class E>
py::enum_<E> bind_enum(py::module_& m, const char* name, const char* doc,
                       std::initializer_list<E> values, E (*from_string)(std::string_view)) {
  py::enum_<E> e(m, name, doc);
  for (E v : values) e.value(std::string(to_string(v)).c_str(), v);
  e.def(py::init([from_string](const std::string& text) { return from_string(text); }),
        py::arg("text"));
  // Replace (not overload) pybind11's "Type.name": str() is the library's name.
  e.attr("__str__") = py::cpp_function([](E v) { return std::string(to_string(v)); },
                                       py::name("__str__"), py::is_method(e));
  e.def_static(
      "from_string", [from_string](const std::string& text) { return from_string(text); },
      py::arg("text"),
      "The value named by its text; raises ValueError naming the accepted values.");
  py::implicitly_convertible<py::str, E>();
  return e;
}

/// A keyword-argument constructor for an options struct: T() with each keyword set as an
/// attribute, so an unknown keyword is an AttributeError and each value is checked by the
/// attribute's own conversion (e.g. SolverOptions(tolerance=1e-12, method="nlopt")).
template <class T, class Class>
void def_keyword_init(Class& cls) {
  cls.def(py::init([](const py::kwargs& kwargs) {
    py::object self = py::cast(T{});
    for (const auto& [key, value] : kwargs) py::setattr(self, key, value);
    return self.cast<T>();
  }));
}

/// A repr listing the given attributes: Name(a=1, b=2).
template <class T>
std::string repr_of(const T& value, const char* name, std::initializer_list<const char*> fields) {
  py::object self = py::cast(value);
  std::string out = std::string(name) + "(";
  bool first = true;
  for (const char* f : fields) {
    out += (first ? "" : ", ") + std::string(f) + "=" + py::repr(self.attr(f)).cast<std::string>();
    first = false;
  }
  return out + ")";
}

// The binding units, each in its own file, called in this order by module.cpp.
void bind_enums(py::module_& m);
void bind_potentials(py::module_& m);
void bind_impacts(py::module_& m);
void bind_scenes(py::module_& m);
void bind_multibody(py::module_& m);
void bind_simulation(py::module_& m);
void bind_curves(py::module_& m);
void bind_batch(py::module_& m);
void bind_atlas(py::module_& m);
void bind_fit(py::module_& m);
void bind_sparse(py::module_& m);

}  // namespace fremond::python
