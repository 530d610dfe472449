#pragma once
// Python values as mo2d laws and motions.
//
// A law (a force component, a torque, a spring tension, an effort; mo2d/law.hpp) is given as
//  - a number: a constant;
//  - an expression string ("-2.0 * crank.w + sin(t)"): parsed by the scene parser
//    (mo2d/expression.hpp); `t` is the time, names in `params` are constants, every other name is
//    a label of the state, resolved by build_model (an unknown label is an Error naming it);
//  - a callable f(t) of time, or mo2d.Law(labels, f) with f(x, t), x the tuple of the labels'
//    values: called with floats, it returns a float. Where mo2d asks for derivatives (the exact
//    Jacobian of CVODE BDF and of linearization, mo2d/jacobian.hpp) they are central differences
//    of the callable along the direction asked (along_curve in laws.cpp); values are exact.
//    Prescribed motions, which need s, s' and s'', are expressions or callables returning the
//    three.
// A callable is called with the GIL held (runs of a System keep it); an exception it raises is
// carried out of the run (across CVODE's C frames too) and raised again in Python with the
// element and the time attached (docs/python.md, "Exceptions of Python code inside a run").
#include <pybind11/pybind11.h>

#include <map>
#include <string>

#include "mo2d/inverse.hpp"
#include "mo2d/law.hpp"

namespace mo2d::py_bind {

using Params = std::map<std::string, double>;

Law expression_law(const std::string& text, const Params& params);
Law callable_law(std::vector<std::string> labels, pybind11::object f);
// None, a number, a string, a callable of t or a Law.
Law to_law(const pybind11::object& value, const Params& params = {});
// A motion s(t) of `coordinate`: an expression of t (exact derivatives) or a callable returning
// (s, s_dot, s_ddot).
Prescribed to_motion(const std::string& coordinate, const pybind11::object& value,
                     const Params& params);

}  // namespace mo2d::py_bind
