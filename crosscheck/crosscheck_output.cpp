// Table and CSV of a cross-check report.
#include <charconv>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "mo2d/crosscheck.hpp"
#include "output/write_file.hpp"

namespace mo2d {

namespace {

void print_channel(std::ostream& out, const char* kind, const ChannelError& c) {
  char line[256];
  std::snprintf(line, sizeof line, "  %-8s %-28s %12.5g %10.3e %10.3e %10.4f\n", kind,
                c.label.c_str(), c.peak, c.rms, c.max, c.max_time);
  out << line;
}

}  // namespace

void print_crosscheck_table(std::ostream& out, const CrosscheckReport& r) {
  char head[512];
  std::snprintf(head, sizeof head,
                "Box2D cross-check: %s, h = %.6g s, %d velocity / %d position iterations, %d "
                "steps (after %d settling steps), %d compared at t_n + %.3g h, feedback time "
                "%.3g s\n",
                r.mechanism.c_str(), r.step, r.velocity_iterations, r.position_iterations, r.steps,
                r.settle_steps, r.compared_steps, r.sample_offset, r.feedback_time);
  out << head;
  for (const std::string& n : r.notes) out << "  note: " << n << "\n";
  char cols[256];
  std::snprintf(cols, sizeof cols, "  %-8s %-28s %12s %10s %10s %10s\n", "kind", "channel", "peak",
                "rms/peak", "max/peak", "at t [s]");
  out << cols;
  for (const ChannelError& c : r.efforts) print_channel(out, "effort", c);
  for (const ChannelError& c : r.reactions) print_channel(out, "reaction", c);
  char tail[256];
  std::snprintf(tail, sizeof tail, "  tracking error %.3e (rad or m), CPU %.3f s: %s\n",
                r.tracking_error, r.cpu_seconds, r.agree ? "AGREE" : "DISAGREE");
  out << tail;
  for (const std::string& f : r.failures) out << "  " << f << "\n";
}

std::string crosscheck_csv(const CrosscheckReport& r) {
  std::string s = "t";
  for (const std::string& l : r.effort_labels) s += ",mo2d." + l + ",box2d." + l;
  for (const std::string& l : r.reaction_labels) s += ",mo2d." + l + ",box2d." + l;
  s += "\n";
  // the shortest text that reads back to the same double (as mo2d's own CSV, mo2d/csv.hpp)
  auto put = [&s](double v) {
    char buf[32];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    s.append(buf, end);
  };
  for (Eigen::Index k = 0; k < r.time.size(); ++k) {
    put(r.time[k]);
    for (Eigen::Index c = 0; c < r.mo2d_efforts.cols(); ++c) {
      s += ',';
      put(r.mo2d_efforts(k, c));
      s += ',';
      put(r.box2d_efforts(k, c));
    }
    for (Eigen::Index c = 0; c < r.mo2d_reactions.cols(); ++c) {
      s += ',';
      put(r.mo2d_reactions(k, c));
      s += ',';
      put(r.box2d_reactions(k, c));
    }
    s += "\n";
  }
  return s;
}

void write_crosscheck_csv(const CrosscheckReport& r, const std::string& path) {
  write_file_atomically(path, crosscheck_csv(r));
}

}  // namespace mo2d
