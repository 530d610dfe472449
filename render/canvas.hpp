#pragma once
// Cairo plumbing shared by frames and plots: a surface + context that owns its output (PNG
// image, or SVG/PDF bytes written to memory), colour and text helpers. Internal to mo2d_render.
#include <cairo.h>

#include <memory>
#include <numbers>
#include <string>

#include "mo2d/render/image.hpp"

namespace mo2d::detail {

inline constexpr double kPi = std::numbers::pi;

enum class Format { png, svg, pdf };
// The format named by the extension of `path` (.png, .svg, .pdf); throws Error otherwise.
Format format_of(const std::string& path);

// Drawing units are pixels for every format: vector surfaces are width*72/dpi points wide and
// scaled by 72/dpi, so one drawing routine serves all three.
class Canvas {
 public:
  Canvas(Format format, int width, int height, double dpi);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  double px(double points) const { return points * dpi_ / 72.0; }  // points -> pixels
  // The image (PNG canvas only).
  Image image() const;
  // The encoded file: PNG, SVG or PDF bytes. Ends the drawing.
  std::string finish();

 private:
  Format format_;
  double dpi_;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
  std::unique_ptr<std::string> bytes_;  // vector output (stable address for Cairo's callback)
};

// Throws Error if the size or dpi is not usable.
void check_size(int width, int height, double dpi, const std::string& what);
// Throws Error naming `what` if Cairo reports an error on the context.
void check_status(cairo_t* cr, const std::string& what);

void set_colour(cairo_t* cr, const Rgb& c, double alpha = 1.0);
// cairo_select_font_face, the family spelt in capitals on a pixel image and in small letters on
// an SVG or PDF surface (fontconfig matches families whatever their case). Cairo 1.16 resolves a
// toy font face once, with the font options of the first surface that draws with it, and keeps
// it: with one spelling, an SVG drawn first (no hinting) left the text of every later PNG of the
// process unhinted, so a picture's bytes depended on what the process drew before it. Two
// spellings are two faces, each resolved with its own kind of surface.
void select_font(cairo_t* cr, const std::string& family, cairo_font_slant_t slant,
                 cairo_font_weight_t weight);
Rgb mix(const Rgb& a, const Rgb& b, double t);  // (1 - t) a + t b

// Text with its anchor: ax = 0 left, 0.5 centre, 1 right; ay = 0 top, 0.5 middle, 1 baseline.
void draw_text(cairo_t* cr, const std::string& text, double x, double y, double ax, double ay);
double text_width(cairo_t* cr, const std::string& text);

// Write bytes atomically, creating nothing; Error names the path.
void write_bytes(const std::string& path, const std::string& bytes);

}  // namespace mo2d::detail
