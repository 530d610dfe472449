// The command-line tool's entry points: everything a run can be drawn as, written under one
// folder, and the plots of inverse and forward results.
#include "mo2d/render/run.hpp"

#include <cstdlib>
#include <filesystem>
#include <string>

#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/output.hpp"

namespace mo2d {

namespace {

std::vector<double> column(const Eigen::MatrixXd& M, Eigen::Index c) {
  const Eigen::VectorXd v = M.col(c);
  return {v.data(), v.data() + v.size()};
}
std::vector<double> values(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

Plot time_plot(const Eigen::VectorXd& t) {
  Plot p;
  p.x.label = "time (s)";
  if (t.size() > 0) p.x.range = std::pair{t.minCoeff(), t.maxCoeff()};
  if (t.size() > 0 && !(t.maxCoeff() > t.minCoeff())) p.x.range.reset();
  return p;
}

// Exact zeros cannot be drawn on a log axis: if no residual is positive, say so and keep the axes.
void mark_all_zero(Plot& p) {
  for (const Series& s : p.series)
    for (double v : s.y)
      if (v > 0) return;
  p.y.range = std::pair{1e-18, 1e-12};
  p.title += " (all exactly zero)";
}

void check_job(const RenderJob& job) {
  if (job.format != "png" && job.format != "svg" && job.format != "pdf")
    throw Error("render: RenderJob::format '" + job.format + "' is not png, svg or pdf", "format");
  if (job.name.empty() || job.name.find('/') != std::string::npos)
    throw Error("render: RenderJob::name '" + job.name + "' must be a plain file name", "name");
  std::error_code ec;
  std::filesystem::create_directories(job.dir, ec);
  if (ec)
    throw Error("render: cannot create the folder '" + job.dir + "': " + ec.message(), job.dir);
}

std::string path_of(const RenderJob& job, const std::string& what, const std::string& ext) {
  return (std::filesystem::path(job.dir) / (job.name + "_" + what + "." + ext)).string();
}

RenderOutputs render_motion(const Model& model, const Motion& motion, const RenderJob& job,
                            const std::vector<std::pair<std::string, Plot>>& plots) {
  check_job(job);
  RenderOutputs out;
  if (job.filmstrip) {
    out.filmstrip = path_of(job, "filmstrip", job.format);
    write_filmstrip(model, motion, job.filmstrip_options, out.filmstrip);
  }
  if (job.frames || job.video)
    out.frames = write_frames(model, motion, job.frame, job.dir, job.name, job.every);
  if (job.video) {
    const std::string mp4 = (std::filesystem::path(job.dir) / (job.name + ".mp4")).string();
    const double fps = job.fps;
    if (encode_video(job.dir, job.name, fps, mp4))
      out.video = mp4;
    else
      out.notes.push_back("ffmpeg not found on PATH: no video");
  }
  for (const auto& [what, plot] : plots) {
    Plot p = plot;
    p.width = job.plot_width;
    p.height = job.plot_height;
    p.dpi = job.plot_dpi;
    out.plots.push_back(path_of(job, what, job.format));
    write_plot(p, out.plots.back());
  }
  return out;
}

}  // namespace

Plot efforts_plot(const Trajectory& r) {
  Plot p = time_plot(r.time);
  bool torque = false, force = false;
  for (size_t u = 0; u < r.input_labels.size(); ++u) {
    torque |= ends_with(r.input_labels[u], ".torque");
    force |= ends_with(r.input_labels[u], ".force");
    p.series.push_back({r.input_labels[u], values(r.time), column(r.efforts, u), {}, false, false});
  }
  p.y.label = torque && force ? "effort (N\u00B7m, N)" : force ? "force (N)" : "torque (N\u00B7m)";
  p.title = "Actuator efforts";
  return p;
}

// Constraint residuals (columns of `residuals`: position, velocity[, acceleration]) on a log axis.
Plot residuals_plot(const Trajectory& r) {
  const Eigen::VectorXd& time = r.time;
  const Eigen::MatrixXd& residuals = r.residuals;
  Plot p = time_plot(time);
  const char* names[] = {"position (m)", "velocity", "acceleration"};
  for (int c = 0; c < 3 && c < residuals.cols(); ++c)
    p.series.push_back({names[c], values(time), column(residuals, c), {}, c > 0, false});
  p.y.label = "constraint residual |\u03C8|\u221E";
  p.y.log = true;
  p.title = "Constraint residuals";
  mark_all_zero(p);
  return p;
}

Plot energies_plot(const Trajectory& r) {
  Plot p = time_plot(r.time);
  // K + V - W + D, not its deviation from the start: the curve is flat at K + V (t0)
  const Eigen::VectorXd balance =
      energy_balance(r).array() + (r.kinetic.size() ? r.kinetic[0] + r.potential[0] : 0.0);
  p.series.push_back({"kinetic", values(r.time), values(r.kinetic), {}, false, false});
  p.series.push_back({"potential", values(r.time), values(r.potential), {}, false, false});
  if (r.input_work.size() == r.time.size())
    p.series.push_back({"input work", values(r.time), values(r.input_work), {}, true, false});
  if (r.load_work.size() == r.time.size() && r.load_work.cwiseAbs().maxCoeff() > 0)
    p.series.push_back({"load work", values(r.time), values(r.load_work), {}, true, false});
  if (r.constraint_work.size() == r.time.size() && r.constraint_work.cwiseAbs().maxCoeff() > 0)
    p.series.push_back(
        {"constraint work", values(r.time), values(r.constraint_work), {}, true, false});
  if (r.dissipated.size() == r.time.size())
    p.series.push_back({"dissipated", values(r.time), values(r.dissipated), {}, true, false});
  if (balance.size() == r.time.size())
    p.series.push_back(
        {"K + V \u2212 W + D", values(r.time), values(balance), rgb_hex(0x222222), false, false});
  p.y.label = "energy (J)";
  p.title = "Energies";
  return p;
}

RenderOutputs render_run(const Model& model, const Trajectory& result, const RenderJob& job) {
  std::vector<std::pair<std::string, Plot>> plots;
  if (job.plots) {
    if (result.has_energies())
      plots.push_back({"energies", energies_plot(result)});
    else if (result.efforts.cols() > 0)
      plots.push_back({"efforts", efforts_plot(result)});
    plots.push_back({"residuals", residuals_plot(result)});
  }
  const Motion motion = motion_of(result);
  return render_motion(model, motion, job, plots);
}

bool encode_video(const std::string& dir, const std::string& name, double fps,
                  const std::string& path) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) return false;
  if (!(fps > 0)) throw Error("render: video frame rate must be > 0", "fps");
  if (OutputSet* set = OutputSet::active()) set->commit();  // ffmpeg reads the frames by name
  auto quote = [](const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string tmp = path + ".tmp.mp4";
  const std::string cmd = "ffmpeg -loglevel error -y -framerate " + std::to_string(fps) + " -i " +
                          quote((std::filesystem::path(dir) / (name + "_%04d.png")).string()) +
                          " -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -c:v libx264 -pix_fmt yuv420p " +
                          quote(tmp);
  if (std::system(cmd.c_str()) != 0) {
    std::filesystem::remove(tmp);
    throw Error("render: ffmpeg failed to write '" + path + "'", path);
  }
  std::filesystem::rename(tmp, path);
  return true;
}

}  // namespace mo2d
