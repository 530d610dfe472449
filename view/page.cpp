// The viewer page (mo2d/view.hpp): the run's drawing (mo2d/render/drawing.hpp) and columns at
// the chosen samples, written as one JSON object into the page template (view/viewer.html,
// embedded at build time as kViewerTemplate).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "mo2d/csv.hpp"
#include "mo2d/error.hpp"
#include "mo2d/render/drawing.hpp"
#include "mo2d/view.hpp"
#include "model/suggest.hpp"
#include "output/write_file.hpp"
#include "viewer_template.hpp"

namespace mo2d {

namespace {

// A JSON string; '<', '>' and '&' escaped too, so that no name can close the page's <script>.
std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      o += '\\';
      o += ch;
    } else if (c < 0x20 || c == '<' || c == '>' || c == '&') {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else {
      o += ch;
    }
  }
  return o + "\"";
}

// A number in at most `digits` significant digits; null when not finite.
std::string number(double v, int digits = 6) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// A pixel coordinate to 0.01 px.
std::string pixel(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

std::string rgb(const Rgb& c) {
  std::string s(1, '[');
  s += number(c.r, 4) + "," + number(c.g, 4) + "," + number(c.b, 4) + "]";
  return s;
}

void points(std::string& o, const std::vector<Vec2>& v) {
  o += '[';
  for (size_t k = 0; k < v.size(); ++k) {
    if (k) o += ',';
    o += pixel(v[k].x()) + "," + pixel(v[k].y());
  }
  o += ']';
}

// "2nd", "3rd", "11th", "21st"
std::string ordinal(int n) {
  const int tens = n % 100, ones = n % 10;
  const char* suffix = tens >= 11 && tens <= 13 ? "th"
                       : ones == 1              ? "st"
                       : ones == 2              ? "nd"
                       : ones == 3              ? "rd"
                                                : "th";
  return std::to_string(n) + suffix;
}

std::vector<int> chosen_samples(int n, int max_frames, int& stride) {
  stride = n <= max_frames ? 1 : (n - 2) / (max_frames - 1) + 1;
  std::vector<int> s;
  for (int k = 0; k < n; k += stride) s.push_back(k);
  if (s.back() != n - 1) s.push_back(n - 1);
  return s;
}

std::vector<std::string> plotted(const Trajectory& r, const std::vector<std::string>& asked,
                                 const std::vector<std::string>& labels) {
  if (!asked.empty()) {
    for (const std::string& c : asked)
      if (std::find(labels.begin(), labels.end(), c) == labels.end())
        throw Error("unknown column '" + c + "'" + did_you_mean(c, labels) +
                        ": the columns are the CSV header of the run (" + labels.front() +
                        (labels.size() > 1 ? ", " + labels[1] : "") + ", ...)",
                    c);
    return asked;
  }
  if (!r.input_labels.empty()) return r.input_labels;
  if (!r.coordinate_labels.empty()) return {r.coordinate_labels.front()};
  return {};
}

// Columns shown for a body or joint clicked: those whose label starts with its name and a dot.
bool belongs(const std::string& label, const std::set<std::string>& names) {
  for (size_t dot = label.find('.'); dot != std::string::npos; dot = label.find('.', dot + 1))
    if (names.contains(label.substr(0, dot))) return true;
  return false;
}

std::string style_json(const Drawing& d) {
  const FrameStyle& s = d.style;
  return "{\"line\":" + number(d.line_width) + ",\"joint_r\":" + number(d.joint_radius) +
         ",\"com_r\":" + number(d.com_radius) + ",\"block_hl\":" + number(d.block_half_length) +
         ",\"block_hh\":" + number(d.block_half_height) + ",\"slot_w\":" + number(d.slot_width) +
         ",\"background\":" + rgb(s.background) + ",\"ink\":" + rgb(s.ink) +
         ",\"joint_fill\":" + rgb(s.joint_fill) + ",\"ground\":" + rgb(s.ground) +
         ",\"font\":" + quoted(s.font) + "}";
}

std::string geometry_json(const Drawing& d) {
  std::string o = ",\"bodies\":[";
  for (size_t b = 0; b < d.body_names.size(); ++b) {
    if (b) o += ',';
    o += std::string("{\"name\":") + quoted(d.body_names[b]) +
         ",\"colour\":" + rgb(d.body_colours[b]) + ",\"width\":" + number(d.body_widths[b]) +
         ",\"com\":" + (d.body_has_com[b] ? "true" : "false") + "}";
  }
  o += "],\"joints\":[";
  for (size_t j = 0; j < d.joints.size(); ++j) {
    const DrawnJoint& J = d.joints[j];
    if (j) o += ',';
    o += std::string("{\"name\":") + quoted(J.name) + ",\"kind\":" + quoted(J.kind) +
         ",\"b1\":" + std::to_string(J.body1) + ",\"b2\":" + std::to_string(J.body2) +
         ",\"pivot\":" + (J.ground_pivot ? "1" : "0") + "}";
  }
  o += "],\"contacts\":[";
  for (size_t c = 0; c < d.contacts.size(); ++c) {
    const DrawnContact& C = d.contacts[c];
    if (c) o += ',';
    o += std::string("{\"name\":") + quoted(C.name) + ",\"target\":" + quoted(C.target) +
         ",\"pb\":" + std::to_string(C.point_body) + ",\"tb\":" + std::to_string(C.target_body) +
         ",\"r\":" + number(C.radius) + ",\"R\":" + number(C.target_radius) +
         ",\"hw\":" + number(C.half_width) + "}";
  }
  o += "],\"t\":[";
  for (size_t f = 0; f < d.samples.size(); ++f) {
    if (f) o += ',';
    o += number(d.samples[f].time, 10);
  }
  // per frame: hulls (per body), joints, coms; rails and axes of the joints that are not
  // revolute; each contact's point p and target points a, b
  o += "],\"frames\":[";
  for (size_t f = 0; f < d.samples.size(); ++f) {
    const DrawnSample& s = d.samples[f];
    o += f ? ",{\"H\":[" : "{\"H\":[";
    for (size_t b = 0; b < s.hulls.size(); ++b) {
      if (b) o += ',';
      points(o, s.hulls[b]);
    }
    o += "],\"J\":";
    points(o, s.joints);
    o += ",\"C\":";
    points(o, s.coms);
    std::vector<Vec2> rails;
    for (size_t j = 0; j < d.joints.size(); ++j)
      if (d.joints[j].kind != "revolute")
        rails.insert(rails.end(), {s.rails[j].first, s.rails[j].second, s.axes[j]});
    o += ",\"R\":";
    points(o, rails);
    std::vector<Vec2> contacts;  // per contact: p, a, b
    for (const std::array<Vec2, 3>& c : s.contacts)
      contacts.insert(contacts.end(), c.begin(), c.end());
    o += ",\"K\":";
    points(o, contacts);
    o += '}';
  }
  return o + "]";
}

}  // namespace

ViewerPage viewer_page(const Model& model, const Trajectory& run, const ViewerOptions& options) {
  if (options.max_frames < 2)
    throw Error("viewer: max_frames is " + std::to_string(options.max_frames) + ", must be >= 2",
                "max_frames");
  const int n = static_cast<int>(run.time.size());
  if (n == 0) throw Error("viewer: the run has no samples", "time");
  const auto columns = trajectory_columns(run);
  std::vector<std::string> labels;
  labels.reserve(columns.size());
  for (const auto& c : columns) labels.push_back(c.first);
  const std::vector<std::string> plots = plotted(run, options.columns, labels);

  ViewerPage page;
  page.samples = n;
  const std::vector<int> samples = chosen_samples(n, options.max_frames, page.stride);
  page.frames = static_cast<int>(samples.size());
  const Drawing d = drawing_of(model, motion_of(run), options.frame, samples);
  if (page.stride > 1)
    page.notes.push_back(std::to_string(page.frames) + " of " + std::to_string(n) +
                         " samples in the page (every " + ordinal(page.stride) +
                         " and the last; at most " + std::to_string(options.max_frames) + ")");

  std::set<std::string> names(d.body_names.begin(), d.body_names.end());
  for (const DrawnJoint& j : d.joints) names.insert(j.name);
  const std::vector<std::string> units = trajectory_csv_units(model, run);
  std::string values = ",\"values\":{", unit = ",\"units\":{";
  bool first = true;
  for (size_t c = 0; c < columns.size(); ++c) {
    const auto& [label, x] = columns[c];
    const bool plot = std::find(plots.begin(), plots.end(), label) != plots.end();
    if (!plot && !belongs(label, names)) continue;
    if (!first) values += ',';
    values += quoted(label) + ":[";
    if (!first) unit += ',';
    unit += quoted(label) + ":" + quoted(units[c]);
    first = false;
    for (size_t f = 0; f < samples.size(); ++f) {
      const double v = x[samples[f]];
      if (!std::isfinite(v) && plot)
        page.notes.push_back("column '" + label + "' is not finite (" + number(v) + ") at t = " +
                             number(run.time[samples[f]], 10) + " s: a gap in its plot");
      if (f) values += ',';
      values += number(v);
    }
    values += ']';
  }
  values += '}';
  unit += '}';
  std::string plot_list = ",\"plots\":[";
  for (size_t k = 0; k < plots.size(); ++k) {
    if (k) plot_list += ',';
    plot_list += quoted(plots[k]);
  }
  plot_list += ']';
  std::string notes = ",\"notes\":[";
  for (size_t k = 0; k < page.notes.size(); ++k) {
    if (k) notes += ',';
    notes += quoted(page.notes[k]);
  }
  notes += ']';

  const std::string title =
      options.title.empty() ? model.name + ": " + to_string(run.kind) + " dynamics" : options.title;
  const std::string data =
      "{\"title\":" + quoted(title) + ",\"kind\":" + quoted(to_string(run.kind)) +
      ",\"samples\":" + std::to_string(n) + ",\"stride\":" + std::to_string(page.stride) +
      ",\"width\":" + number(d.view.width) + ",\"height\":" + number(d.view.height) +
      ",\"scale\":" + number(d.view.scale, 12) + ",\"centre\":[" + number(d.view.centre.x(), 12) +
      "," + number(d.view.centre.y(), 12) + "],\"style\":" + style_json(d) + geometry_json(d) +
      values + unit + plot_list + notes + "}";

  std::string html(detail::kViewerTemplate);
  const std::string slot = "/*MO2D_DATA*/null";
  const size_t at = html.find(slot);
  if (at == std::string::npos) throw Error("viewer: the page template has no data slot");
  html.replace(at, slot.size(), data);
  const std::string title_slot = "<!--MO2D_TITLE-->";
  for (size_t t = html.find(title_slot); t != std::string::npos; t = html.find(title_slot)) {
    std::string escaped;
    for (const char c : title)
      escaped += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    html.replace(t, title_slot.size(), escaped);
  }
  page.html = std::move(html);
  return page;
}

ViewerPage write_viewer_page(const Model& model, const Trajectory& run,
                             const ViewerOptions& options, const std::string& path) {
  ViewerPage page = viewer_page(model, run, options);
  write_file_atomically(path, page.html);
  return page;
}

}  // namespace mo2d
