// mo2d._mo2d: the compiled part of the Python package mo2d (python/mo2d/__init__.py re-exports
// it). See docs/python.md.
#include <cmath>
#include <exception>
#include <limits>

#include "bindings.hpp"
#include "mo2d/budget.hpp"
#include "mo2d/error.hpp"
#include "mo2d/expression.hpp"
#include "mo2d/run_stop.hpp"
#include "mo2d/scene.hpp"

namespace mo2d::py_bind {

namespace {

// The class objects of mo2d.Error and mo2d.ColumnError, created once by bind_errors (they live as
// long as the module).
PyObject* error_class = nullptr;
PyObject* column_error_class = nullptr;

// Raise mo2d.Error(message) (or `cls`, a subclass) with the element, time and (scene files)
// location of the error.
void raise_error(const Error& e, const Location* where, int column,
                 PyObject* cls_object = error_class) {
  py::object cls = py::reinterpret_borrow<py::object>(cls_object);
  py::object instance = cls(e.what());
  instance.attr("message") = py::str(e.what());
  instance.attr("element") = py::str(e.element());
  instance.attr("time") = py::float_(e.time());
  if (where != nullptr) {
    instance.attr("file") = py::str(where->file);
    instance.attr("line") = py::int_(where->line);
    instance.attr("column") = py::int_(where->column);
  } else if (column > 0) {
    instance.attr("column") = py::int_(column);
  }
  PyErr_SetObject(cls_object, instance.ptr());
}

// An Error that carries an exception of Python code (a law's, raised inside a run and nested by
// the run, src/dynamics/laws.cpp): that Python exception raised again as it was (its type, its
// message), with the Error's message ("torque 'kick' failed at t = 0.5 s: ...") added as a note
// (PEP 678, shown under the traceback) and as the attributes mo2d_message, mo2d_element and
// mo2d_time. false (nothing raised) when e carries none.
bool raise_nested_python(const Error& e) {
  const auto* nested = dynamic_cast<const std::nested_exception*>(&e);
  if (nested == nullptr || !nested->nested_ptr()) return false;
  try {
    nested->rethrow_nested();
  } catch (py::error_already_set& python) {
    const py::object& value = python.value();
    try {
      if (py::hasattr(value, "add_note")) value.attr("add_note")(py::str(e.what()));
      value.attr("mo2d_message") = py::str(e.what());
      value.attr("mo2d_element") = py::str(e.element());
      value.attr("mo2d_time") = py::float_(e.time());
    } catch (py::error_already_set&) {  // an exception without a __dict__: raised as it is
    }
    python.restore();
    return true;
  } catch (...) {  // a C++ exception: the Error alone
  }
  return false;
}

// Ctrl-C during a run (mo2d/budget.hpp, interrupts): runs poll this about every 0.05 s. On
// Python's main thread (the only one that runs signal handlers) it takes the GIL (released by the
// scene runs, held by the System runs: PyGILState_Ensure either way) and runs the pending signal
// handlers; an exception one raised (KeyboardInterrupt) is kept and the run ends by Interrupted,
// which the translator below turns back into that exception. Other threads: never interrupted
// (and never wait for the GIL here).
unsigned long main_thread_ident = 0;
PyObject *pending_type = nullptr, *pending_value = nullptr, *pending_traceback = nullptr;

bool finalizing() {
#if PY_VERSION_HEX >= 0x030D0000
  return Py_IsFinalizing() != 0;
#else
  return _Py_IsFinalizing() != 0;
#endif
}

bool python_interrupt_check() {
  if (PyThread_get_thread_ident() != main_thread_ident || finalizing()) return false;
  const PyGILState_STATE gil = PyGILState_Ensure();
  const bool raised = PyErr_CheckSignals() != 0;
  if (raised) {
    Py_XDECREF(pending_type);
    Py_XDECREF(pending_value);
    Py_XDECREF(pending_traceback);
    PyErr_Fetch(&pending_type, &pending_value, &pending_traceback);
  }
  PyGILState_Release(gil);
  return raised;
}

// The exception the signal handler raised (KeyboardInterrupt unless the user's handler raises
// another), raised again now that the run has unwound.
void raise_interrupt() {
  if (pending_type == nullptr) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    return;
  }
  PyErr_Restore(pending_type, pending_value, pending_traceback);  // steals the references
  pending_type = pending_value = pending_traceback = nullptr;
}

}  // namespace

void bind_interrupts() {
  main_thread_ident =
      py::module_::import("threading").attr("main_thread")().attr("ident").cast<unsigned long>();
  set_interrupt_check(&python_interrupt_check);
}

void bind_errors(py::module_& m) {
  error_class = PyErr_NewExceptionWithDoc(
      "mo2d.Error",
      "An error of mo2d: the message names the element, the time of a run and, for scene files, "
      "file:line:column. Attributes: message, element ('' if none), time (NaN outside a run), "
      "file, line, column (scene and expression errors; '' and 0 otherwise).",
      PyExc_Exception, nullptr);
  if (error_class == nullptr) throw py::error_already_set();
  py::object cls = py::reinterpret_borrow<py::object>(error_class);
  cls.attr("message") = py::str("");
  cls.attr("element") = py::str("");
  cls.attr("time") = py::float_(std::numeric_limits<double>::quiet_NaN());
  cls.attr("file") = py::str("");
  cls.attr("line") = py::int_(0);
  cls.attr("column") = py::int_(0);
  m.add_object("Error", cls);

  // mo2d.ColumnError(mo2d.Error, KeyError): `except KeyError` and `except mo2d.Error` both catch
  // it; str() is the message itself (KeyError's str() would quote it as a repr).
  const py::tuple bases = py::make_tuple(cls, py::handle(PyExc_KeyError));
  column_error_class = PyErr_NewExceptionWithDoc(
      "mo2d.ColumnError",
      "A label that is not a column of a result (r['pivot.torq']): a mo2d.Error and a KeyError. "
      "The message names the closest column when one is near (\"did you mean 'pivot.torque'?\"); "
      "element is the label asked for; r.columns lists the labels.",
      bases.ptr(), nullptr);
  if (column_error_class == nullptr) throw py::error_already_set();
  py::object column_cls = py::reinterpret_borrow<py::object>(column_error_class);
  column_cls.attr("__str__") =
      py::module_::import("builtins").attr("BaseException").attr("__str__");
  m.add_object("ColumnError", column_cls);
  // by value: pybind11's translator type is void (*)(std::exception_ptr)
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      raise_error(e, &e.where(), 0);
    } catch (const ColumnError& e) {
      raise_error(e, nullptr, 0, column_error_class);
    } catch (const ExpressionError& e) {
      raise_error(e, nullptr, e.column());
    } catch (const Error& e) {
      if (!raise_nested_python(e)) raise_error(e, nullptr, 0);
    } catch (const Interrupted&) {
      raise_interrupt();
    }
  });
}

}  // namespace mo2d::py_bind

PYBIND11_MODULE(_mo2d, m) {
  m.doc() = "mo2d: dynamics of planar mechanisms (compiled part; see docs/python.md)";
  m.attr("__version__") = MO2D_VERSION;  // project(mo2d VERSION ...) of CMakeLists.txt
  using namespace mo2d::py_bind;
  bind_errors(m);
  bind_interrupts();
  bind_results(m);
  bind_scene(m);
  bind_system(m);
  bind_render(m);
  bind_view(m);
  bind_modes(m);
  bind_design(m);
#ifdef MO2D_HAVE_NLOPT
  bind_optimize(m);
#endif
}
