#pragma once
// Box2D cross-check reports (mo2d/crosscheck.hpp) as Python dicts, with NumPy time series.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "mo2d/crosscheck.hpp"

namespace mo2d::py_bind {

inline pybind11::list channel_list(const std::vector<ChannelError>& channels) {
  pybind11::list out;
  for (const auto& c : channels) {
    pybind11::dict d;
    d["label"] = c.label;
    d["peak"] = c.peak;
    d["rms"] = c.rms;
    d["max"] = c.max;
    d["max_time"] = c.max_time;
    out.append(d);
  }
  return out;
}

inline pybind11::dict crosscheck_dict(const CrosscheckReport& r) {
  pybind11::dict d;
  d["mechanism"] = r.mechanism;
  d["agree"] = r.agree;
  d["failures"] = r.failures;
  d["notes"] = r.notes;
  d["step"] = r.step;
  d["compared_steps"] = r.compared_steps;
  d["effort_rms"] = r.effort_rms;
  d["effort_max"] = r.effort_max;
  d["reaction_rms"] = r.reaction_rms;
  d["reaction_max"] = r.reaction_max;
  d["tracking_error"] = r.tracking_error;
  d["efforts"] = channel_list(r.efforts);
  d["reactions"] = channel_list(r.reactions);
  d["cpu_seconds"] = r.cpu_seconds;
  d["time"] = r.time;
  d["effort_labels"] = r.effort_labels;
  d["mo2d_efforts"] = r.mo2d_efforts;
  d["box2d_efforts"] = r.box2d_efforts;
  return d;
}

// 'agree' as the command line judges it: both largest errors within their tolerances; when not,
// 'box2d_cause' says whether Box2D is the cause (its branch switch or energy drift).
inline pybind11::dict crosscheck_dict(const ForwardCrosscheck& r,
                                      double position_tolerance = kForwardPositionTolerance,
                                      double angle_tolerance = kForwardAngleTolerance) {
  pybind11::dict d;
  d["mechanism"] = r.mechanism;
  const bool agree = forward_agrees(r, position_tolerance, angle_tolerance);
  d["agree"] = agree;
  d["position_tolerance"] = position_tolerance;
  d["angle_tolerance"] = angle_tolerance;
  d["branch_switch"] = r.branch_switch;
  d["box2d_cause"] = agree ? std::string() : box2d_cause(r, position_tolerance, angle_tolerance);
  d["notes"] = r.notes;
  d["step"] = r.step;
  d["steps"] = r.steps;
  d["max_position_error"] = r.max_position_error;
  d["max_angle_error"] = r.max_angle_error;
  d["final_position_error"] = r.final_position_error;
  d["final_angle_error"] = r.final_angle_error;
  d["relative_position_error"] = r.relative_position_error;
  d["time"] = r.time;
  d["position_error"] = r.position_error;
  d["angle_error"] = r.angle_error;
  return d;
}

}  // namespace mo2d::py_bind
