#pragma once
// Everything a run's frames share, computed once: validated input, the joints, the fixed view,
// the peak of every effort, the range of every slider, the traced paths. Internal to mo2d_render.
#include <cairo.h>

#include <array>
#include <utility>
#include <vector>

#include "mo2d/render/frame.hpp"
#include "parts.hpp"

namespace mo2d::detail {

struct FramePlan {
  const Model* model = nullptr;
  const Motion* motion = nullptr;
  FrameOptions options{};
  double P = 1;  // pixels per point
  Parts parts{};
  View view{};
  std::vector<double> peak{};                      // per input: max |effort| over the run
  std::vector<std::pair<double, double>> range{};  // per joint: slider coordinate min, max
  std::vector<TracePoint> trace_points{};
  std::vector<std::vector<Vec2>> traces{};  // per trace point, per sample (world)
  // show_loads: per sample, every force's point and value (world), every torque's centre (its
  // body's centre of mass) and value; the run's peak of each (max |F|, max |torque|)
  struct LoadAt {
    Vec2 at{0, 0}, force{0, 0};
    double torque = 0;
  };
  std::vector<std::vector<LoadAt>> forces{}, torques{};  // [sample][load]
  std::vector<double> force_peak{}, torque_peak{};
  // chains: per sample, each chain's sprocket centres, its spans' tangent points (upper, lower;
  // from a to b) and tensions; the run's peak tension of each chain (chains.cpp)
  struct ChainAt {
    Vec2 ca{0, 0}, cb{0, 0};
    std::array<std::pair<Vec2, Vec2>, 2> span{};
    std::array<double, 2> tension{0, 0};
  };
  std::vector<std::vector<ChainAt>> chains{};  // [sample][chain]
  std::vector<double> chain_peak{};
  // contacts (FrameOptions::contacts): per sample, each contact's moving point p and its target's
  // points a, b (b = a for a circle or a hole; world); per contact, the bodies of p and of a
  // (-1: ground) for their colours (contacts.cpp)
  struct ContactAt {
    Vec2 p{0, 0}, a{0, 0}, b{0, 0};
  };
  std::vector<std::vector<ContactAt>> contacts{};  // [sample][contact]
  std::vector<std::pair<int, int>> contact_bodies{};
  int time_decimals = 2;
};

// Validates (Error: empty run, wrong number of columns, non-finite coordinate, bad size).
FramePlan make_plan(const Model& model, const Motion& motion, const FrameOptions& options);

struct Decorations {
  bool time = true, scale_bar = true, axes = true;
};
// Draws sample `k` in the rectangle (0, 0, view.width, view.height) of cr.
void draw_frame(cairo_t* cr, const FramePlan& plan, int k, const Decorations& decorations);

void check_sample(const Motion& motion, int sample);

// The loads of every sample (FramePlan::forces, torques and their peaks; loads.cpp), and their
// drawing at sample k (after the effort symbols).
void plan_loads(FramePlan& p);
void draw_loads(cairo_t* cr, const FramePlan& p, int k);
// The legend of the load arrows (each load's symbol at its run's peak, with the value) under the
// time stamp, and how many lines it takes.
void draw_load_legend(cairo_t* cr, const FramePlan& p);
int load_legend_lines(const FramePlan& p);
// The chains of every sample (FramePlan::chains; chains.cpp) and their drawing at sample k (pitch
// circles and spans, after the bodies).
void plan_chains(FramePlan& p);
void draw_chains(cairo_t* cr, const FramePlan& p, int k);
// The contacts of every sample (FramePlan::contacts; contacts.cpp), their shapes added to the
// view's box, and their drawing at sample k (after the bodies). Throws Error naming a contact
// whose point is not in the model.
void plan_contacts(FramePlan& p, Eigen::AlignedBox2d& box);
void draw_contacts(cairo_t* cr, const FramePlan& p, int k);

}  // namespace mo2d::detail
