#pragma once
// Private to mo2d_box2d: the budgets of a cross-check (CrosscheckOptions::max_steps,
// max_seconds, max_memory), checked before the run where they can be estimated (Box2D steps,
// result bytes) and during it otherwise (wall-clock seconds, interrupts: run/run_budget.hpp).
#include <string>

#include "mo2d/crosscheck.hpp"
#include "run/run_budget.hpp"

namespace mo2d::crosscheck_detail {

// Refuses `steps` Box2D steps of `h` s (what: "Box2D cross-check of 'name'") above
// check.max_steps (or above what an int counts), with what to change.
void check_box2d_steps(const std::string& what, const std::string& name, double steps, double h,
                       const CrosscheckOptions& check);
// Refuses results of rows x values numbers (about 33 bytes each: 8 in the report's matrices, up
// to 25 in the CSV text) above check.max_memory.
void check_result_memory(const std::string& what, const std::string& name, double rows,
                         double values, const CrosscheckOptions& check);
// The wall-clock budget of the Box2D loop over [t0, t1] (unit: Box2D steps).
detail::RunBudget::Settings box2d_budget(const std::string& what, const std::string& name,
                                         double t0, double t1, const CrosscheckOptions& check);

}  // namespace mo2d::crosscheck_detail
