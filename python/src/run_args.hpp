#pragma once
// Arguments of the runs of a Python-built System (bind_runs.cpp): names of integrators and
// formulations, motions and efforts from Python values (laws.hpp), shared by the whole runs and
// the workspaces (bind_workspace.cpp).
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include "laws.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"

namespace mo2d::py_bind {

using Motions = std::vector<std::pair<std::string, pybind11::object>>;  // label -> Python value

// A count argument (samples, max_steps) from any Python integer: a Python int beyond the C++ int
// is a mo2d.Error naming the argument and the range (pybind11's own conversion would say only
// "incompatible function arguments"); a float or a bool is a TypeError naming it.
int to_count(const pybind11::object& value, const char* name);

// The end time of a run of a System, t0 + duration: duration= is the name of the scene files'
// run.duration, of the command line's --duration and of mo2d.forward / inverse. The end time t1=
// (the C++ options' name, the keyword of these functions until 0.1.0) is still accepted, with a
// DeprecationWarning, for one release; both given is a TypeError. Neither: t0 + default_duration,
// or a TypeError naming the missing argument when default_duration is NaN (no default).
double end_time(const char* function, double t0, const pybind11::object& duration,
                const pybind11::object& t1, double default_duration);

// "rk4" -> Integrator::rk4 (to_string's names); another name is an Error listing them.
Integrator to_integrator(const std::string& s);
Formulation to_formulation(const std::string& s);
// [(coordinate, s(t))]: expressions of t or callables returning (s, s', s'') (to_motion).
std::vector<Prescribed> to_motions(const Motions& motion, const Params& params);
// [(input label, law)] ordered like Model::inputs (an input without a law: none, zero); a label
// the model does not have is an Error naming it.
EffortLaws to_efforts(const Model& m, const Motions& efforts, const Params& params);

// ForwardWorkspace, InverseWorkspace, energy balance, tables, controllers, transmissions and the
// System's gears, racks and constraints (bind_workspace.cpp, bind_extras.cpp); called by
// bind_runs.
void bind_workspace(pybind11::module_& m);
void bind_extras(pybind11::module_& m);

}  // namespace mo2d::py_bind
