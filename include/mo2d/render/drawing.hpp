#pragma once
// What a Cairo frame draws, as numbers: the pixel positions of every body outline, joint, centre
// of mass, slider block, ground symbol and contact of chosen samples, with the sizes and colours of
// the frame's style. Read from the same plan as render_frame (render/plan.hpp), so that another
// drawing of these numbers (the viewer page, mo2d/view.hpp) lands on the same pixels as the
// Cairo frame of the same sample and options.
#include <array>
#include <string>
#include <vector>

#include "mo2d/model.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/render/image.hpp"

namespace mo2d {

// A joint as drawn: revolute (a pin at its node), prismatic (a slider block on a rail) or slot (a
// pin in a slot).
struct DrawnJoint {
  std::string name{}, kind{};  // kind: "revolute", "prismatic" or "slot"
  int body1 = -1, body2 = -1;  // -1: ground
  bool ground_pivot = false;   // a revolute joint to the ground: the pivot symbol below it
  bool pin = true;             // drawn as a pin (revolute, slot); false: a block (prismatic)
};

// A contact as drawn (FrameOptions::contacts, render/contacts.cpp): the circle around its moving
// point and its target, at their size in the world (in pixels here).
struct DrawnContact {
  std::string name{}, target{};           // target: "line", "circle", "hole" or "slot"
  int point_body = -1, target_body = -1;  // -1: the ground (for the colours)
  double radius = 0;  // the circle around the point (pixels; drawn at least 0.6 joint_radius)
  double target_radius = 0;  // a circle's or a hole's radius (pixels)
  double half_width = 0;     // half a slot's width (pixels)
};

// The pixels of one sample (x right, y down, in the frame of FrameOptions::width x height).
struct DrawnSample {
  double time = 0;                         // s
  std::vector<std::vector<Vec2>> hulls{};  // per body: the outline's corners (empty: a block)
  std::vector<Vec2> joints{};              // per joint: the pin's centre, or the block's centre
  std::vector<Vec2> axes{};                // per joint: unit axis (prismatic, slot), else (1, 0)
  std::vector<Vec2> coms{};                // per body: centre of mass
  // per joint: the rail's (prismatic) or slot's ends, the slider's range over the run
  std::vector<std::pair<Vec2, Vec2>> rails{};
  // per contact: its moving point p, its target's points a and b (b = a for a circle or a hole)
  std::vector<std::array<Vec2, 3>> contacts{};
};

// The drawing of chosen samples of a run (drawing_of): what is drawn, the sizes and colours, and
// the pixels of each sample.
struct Drawing {
  View view{};                            // world -> pixels, the same for every sample
  std::vector<std::string> body_names{};  // Model::bodies' names, in order
  std::vector<Rgb> body_colours{};        // per body: the palette's colour
  std::vector<double> body_widths{};     // pixels, per body (one-node and slotted bodies are wider)
  std::vector<bool> body_has_com{};      // mass > 0: the centre-of-mass symbol is drawn
  std::vector<DrawnJoint> joints{};      // the joints drawn, in the order of DrawnSample::joints
  std::vector<DrawnContact> contacts{};  // in the order of DrawnSample::contacts
  // the style's sizes in pixels
  double line_width = 1, joint_radius = 1, com_radius = 1, block_half_length = 1,
         block_half_height = 1, slot_width = 1;
  FrameStyle style{};                  // the colours (FrameOptions::style)
  std::vector<DrawnSample> samples{};  // in the order of drawing_of's `samples`
};

// The drawing of `samples` (indices into the motion) with the view of the whole motion, as
// render_frame(model, motion, k, options) draws sample k. Throws Error as render_frame does.
Drawing drawing_of(const Model& model, const Motion& motion, const FrameOptions& options,
                   const std::vector<int>& samples);

// Sample `sample` drawn as render_frame draws it, as the text of an SVG image (in memory: e.g. a
// System's picture in a notebook, _repr_svg_ of the Python package).
std::string frame_svg(const Model& model, const Motion& motion, int sample,
                      const FrameOptions& options);

}  // namespace mo2d
