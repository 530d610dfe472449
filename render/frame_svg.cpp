// A frame as SVG text in memory (mo2d/render/drawing.hpp): the Cairo frame on an SVG surface.
#include "canvas.hpp"
#include "mo2d/render/drawing.hpp"
#include "plan.hpp"

namespace mo2d {

std::string frame_svg(const Model& model, const Motion& motion, int sample,
                      const FrameOptions& options) {
  detail::check_sample(motion, sample);
  const detail::FramePlan plan = detail::make_plan(model, motion, options);
  detail::Canvas canvas(detail::Format::svg, options.width, options.height, options.dpi);
  detail::draw_frame(canvas.cr(), plan, sample, {});
  return canvas.finish();
}

}  // namespace mo2d
