#pragma once
// Internal: calling user code inside a run (a load law, a prescribed motion: possibly a Python
// callable, python/src/laws.cpp) so that its failures name the element and the time.
#include <cmath>
#include <exception>
#include <string>

#include "mo2d/error.hpp"
#include "run/format.hpp"

namespace mo2d::detail {

// f() for the `role` '`element`' at time t. A mo2d::Error naming no element nor time is rethrown
// as one naming them ("<role> '<element>' failed at t = ... s: <what>"); any other exception (a
// Python callable's, std::bad_alloc) as that Error with the original nested in it
// (std::throw_with_nested), so that a binding can raise the original again
// (python/src/module.cpp) and a driver can tell it from a numerical failure
// (src/forward/forward_cvode.cpp). An Error naming its own element passes unchanged.
template <class F>
auto call_user_code(F&& f, const char* role, const std::string& element, double t) {
  const auto failed = [&](const char* what) {
    return role + std::string(" '") + element + "' failed at t = " + fmt(t) + " s: " + what;
  };
  try {
    return f();
  } catch (const Error& e) {
    if (!e.element().empty() || !std::isnan(e.time())) throw;
    throw Error(failed(e.what()), element, t);
  } catch (const std::exception& e) {
    std::throw_with_nested(Error(failed(e.what()), element, t));
  } catch (...) {
    std::throw_with_nested(Error(failed("an exception of unknown type"), element, t));
  }
}

}  // namespace mo2d::detail
