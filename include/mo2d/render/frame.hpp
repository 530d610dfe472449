#pragma once
// Frames of a mechanism: one configuration drawn off-screen (PNG, SVG or PDF), sequences of
// frames, and contact sheets (filmstrips).
//
// What a frame shows: each body as a thick rounded outline through its nodes (the convex hull
// for three nodes or more), filled with a light tint of its own colour (okabe_ito()); one-node
// bodies as a disc, or as the slider block of their prismatic joint; centres of mass as the
// quartered-circle symbol; revolute joints as circles; prismatic joints as a rail with the slider
// block; pins in slots as a slot cut in the slotted body with the pin; the ground hatched at its
// pivots and rails; actuated joints with an arc (torque) or an arrow (force) whose length and
// colour give the effort relative to the run's peak of that input (red: positive, blue:
// negative); traces of chosen points; optionally the applied loads (FrameOptions::show_loads:
// an arrow from each force's point along the force, a curved arrow around each torque's body,
// sized by the value relative to the run's peak of that load); time stamp, scale bar, axes and
// optional labels (body names); contacts (FrameOptions::contacts): the circle around each one's
// point and the line, circle or hole it touches.
//
// Framing: the view fits the whole motion (every sample of the run) with a margin and is the same
// for every frame of the run; x and y have the same scale (aspect ratio preserved).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "mo2d/contact.hpp"
#include "mo2d/model.hpp"
#include "mo2d/render/image.hpp"
#include "mo2d/trajectory.hpp"

namespace mo2d {

// The samples a frame is drawn from: time, coordinates and (optionally) efforts.
struct Motion {
  Eigen::VectorXd time{};     // samples
  Eigen::MatrixXd q0{};       // samples x Model::n0
  Eigen::MatrixXd efforts{};  // samples x Model::n_inputs(), or 0 columns (no effort symbols)
  // samples x Model::n1, or 0 columns: the quasi-velocities, which the loads drawn with
  // FrameOptions::show_loads may depend on (motion_of fills them)
  Eigen::MatrixXd q1{};
};
// The Motion of a run: its times, coordinates, efforts and quasi-velocities.
Motion motion_of(const Trajectory& r);
// One configuration (e.g. Model::q0) at time t, without efforts.
Motion single_configuration(const Eigen::VectorXd& q0, double t = 0);

// Colours and sizes of a frame (docs/rendering.md, "Frames").
struct FrameStyle {
  // image background
  Rgb background = rgb_hex(0xFFFFFF);
  Rgb ink = rgb_hex(0x222222);         // joints, symbols, text
  Rgb joint_fill = rgb_hex(0xFFFFFF);  // inside of revolute joint circles and pins
  Rgb ground = rgb_hex(0x555555);      // hatching and rails of the ground
  Rgb positive = rgb_hex(0xC0392B);    // effort > 0 (counter-clockwise torque, force along +axis)
  Rgb negative = rgb_hex(0x2166AC);    // effort < 0
  Rgb load = rgb_hex(0x5E3C99);        // applied forces and torques (show_loads): dark violet
  std::vector<Rgb> palette = okabe_ito();  // body k gets palette[k % size]
  // Sizes in points (1/72 in); pixels = points * dpi / 72.
  double body_width = 7.0;      // width of the rounded body outlines
  double line_width = 1.1;      // outlines, rails, symbols
  double joint_radius = 3.4;    // revolute joints and pins
  double com_radius = 3.2;      // centre-of-mass symbol
  double effort_radius = 13.0;  // radius of the torque arcs
  double effort_length = 34.0;  // length of a force arrow at the run's peak force
  // text size (points) and font family
  double font_size = 9.0;
  std::string font = "DejaVu Sans";
};

// What a frame shows and at which size (docs/rendering.md: the table of FrameOptions).
struct FrameOptions {
  int width = 800, height = 600;  // pixels
  double dpi = 96;                // pixels per inch (sizes in FrameStyle are in points)
  double margin = 10;             // points between the motion's extent and the image border
  // Fixed world window (m) instead of fitting the motion: its centre goes to the image centre and
  // it is scaled to fit the image exactly (no margin, no room kept for the decorations).
  std::optional<Eigen::AlignedBox2d> window{};
  bool show_com = true;
  bool show_efforts = true;
  bool show_effort_values = true;  // the values in the top-right corner (tau = ... N m)
  // time stamp, scale bar and x-y axes
  bool show_time = true;
  bool show_scale_bar = true;
  bool show_axes = true;
  bool show_labels = false;  // body names
  // Text at the top left, before the time stamp (e.g. "mode 1: 2.31 Hz, damping ratio 0.052");
  // empty: none.
  std::string title{};
  // Applied forces (Model::forces: arrows from their points, of length style.effort_length at the
  // run's peak |F| of that force) and torques (Model::torques: arcs around their body's centre of
  // mass, sweeping up to 270 degrees at the run's peak, counter-clockwise for a positive torque),
  // in style.load. Their laws are evaluated at (t, q0, q1) of each sample: Motion::q1 is needed.
  bool show_loads = false;
  // Points traced over the whole motion: node labels ("crank.A"), centres of mass ("rod.com") or
  // named points (System::add_point: "tip", "leg.foot").
  std::vector<std::string> traces{};
  // Contacts drawn (a scene's contacts: Scene::contacts): each one's circle around its point and
  // the line, circle or hole it touches, hatched on the obstacle's side (docs/rendering.md).
  std::vector<ContactDef> contacts{};
  FrameStyle style{};
};

// World (m) -> image (pixels): x right, y up in the world; x right, y down in the image.
struct View {
  double scale = 1;              // pixels per metre
  Eigen::Vector2d centre{0, 0};  // world point drawn at the image centre
  double width = 0, height = 0;  // image size in pixels
};
// The pixel (x right, y down) of a world point (m, y up).
Eigen::Vector2d to_pixel(const View& view, const Eigen::Vector2d& world);
// The view of a run: fits every sample (or FrameOptions::window). Throws Error for an empty run,
// a non-finite coordinate (naming it and the time), a size that is not positive.
View fit_view(const Model& model, const Motion& motion, const FrameOptions& options);

// Sample `sample` of the motion drawn into an image of options.width x options.height pixels.
Image render_frame(const Model& model, const Motion& motion, int sample,
                   const FrameOptions& options);
// Same, written to `path`; the format follows the extension: .png, .svg or .pdf (atomic write).
void write_frame(const Model& model, const Motion& motion, int sample, const FrameOptions& options,
                 const std::string& path);
// Every `every`-th sample (the first included) as DIR/NAME_0001.png, DIR/NAME_0002.png, ...
// (DIR is created). Returns the paths written, in order.
std::vector<std::string> write_frames(const Model& model, const Motion& motion,
                                      const FrameOptions& options, const std::string& dir,
                                      const std::string& name, int every = 1);

// A contact sheet: `frames` samples equally spaced over the run (first and last included), or the
// listed `samples`, drawn side by side in `columns` columns (0: one row; default 3), every tile
// with the same view.
struct FilmstripOptions {
  // number of tiles, equally spaced samples
  int frames = 6;
  std::vector<int> samples{};  // these samples instead (then `frames` is ignored)
  // Tiles at evenly spaced values of a phase instead of evenly spaced times, so that a fast
  // periodic motion is not aliased: one phase value per sample (e.g. a crank angle, monotonic)
  // and its cycle (2 pi; a four-stroke engine: 4 pi). The tiles show the run's last whole cycle,
  // at the samples nearest phase_end - cycle + j cycle / frames (j = 0 .. frames - 1). Error if
  // the run covers less than one cycle.
  std::vector<double> phase{};
  double cycle = 0;
  // tiles per row (0: one row)
  int columns = 3;
  double gap = 4;           // points between tiles
  bool tile_border = true;  // a thin frame around every tile
  // Size of one tile (default 360 x 270 px) and what it shows (scale bar and axes: first tile).
  FrameOptions tile{.width = 360, .height = 270};
};
// The filmstrip as an image in memory.
Image render_filmstrip(const Model& model, const Motion& motion, const FilmstripOptions& options);
// .png, .svg or .pdf by extension (atomic write).
void write_filmstrip(const Model& model, const Motion& motion, const FilmstripOptions& options,
                     const std::string& path);

}  // namespace mo2d
