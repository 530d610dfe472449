#pragma once
// Input of the test docs.api_can_fail (docs/api/CMakeLists.txt): one documented and one
// undocumented function, so the API-reference check must report the second one.

namespace mo2d_docs_test {

// Documented: the check accepts it.
double documented_function(double x);

double undocumented_function(double x);

}  // namespace mo2d_docs_test
