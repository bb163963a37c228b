// meridian::Error → meridian.errors.<Class>(message, file=…, line=…, field=…).

#include <exception>
#include <string>

#include "bindings.hpp"
#include "meridian/core/error.hpp"

namespace py = pybind11;

namespace meridian::python {
namespace {

// Raise the Python class `name` of meridian.errors for `e` (the GIL is held in a translator).
void raise(const char* name, const Error& e) {
  const py::object cls = py::module_::import("meridian.errors").attr(name);
  const ErrorContext& c = e.context();
  const py::object none = py::none();
  const py::object file = c.file.empty() ? none : py::str(c.file);
  const py::object line = c.line ? py::int_(*c.line) : none;
  const py::object field = c.field.empty() ? none : py::str(c.field);
  const py::object exc = cls(e.message(), py::arg("file") = file, py::arg("line") = line, py::arg("field") = field);
  PyErr_SetObject(cls.ptr(), exc.ptr());
}

}  // namespace

void register_errors() {
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    // Most derived first: ParseError is an InputError.
    try {
      std::rethrow_exception(p);
    } catch (const ParseError& e) {
      raise("ParseError", e);
    } catch (const InputError& e) {
      raise("InputError", e);
    } catch (const NumericalError& e) {
      raise("NumericalError", e);
    } catch (const IoError& e) {
      raise("IoError", e);
    } catch (const Error& e) {
      raise("Error", e);
    }
  });
}

}  // namespace meridian::python
