// CSV writing (labels in the header, numbers in shortest round-trip form, atomic replace).
#include "mo2d/csv.hpp"

#include <charconv>
#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include "mo2d/error.hpp"
#include "output/write_file.hpp"

namespace mo2d {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Columns of every trajectory: t, coordinates, quasi-velocities, their derivatives (label +
// ".dot"), efforts, reactions.
std::vector<std::string> common_labels(const Trajectory& r) {
  std::vector<std::string> l{"t"};
  l.insert(l.end(), r.coordinate_labels.begin(), r.coordinate_labels.end());
  l.insert(l.end(), r.rate_labels.begin(), r.rate_labels.end());
  for (const auto& x : r.rate_labels) l.push_back(x + ".dot");
  l.insert(l.end(), r.input_labels.begin(), r.input_labels.end());
  l.insert(l.end(), r.reaction_labels.begin(), r.reaction_labels.end());
  return l;
}

// The shortest text that reads back (strtod) to the same double, appended to `s`.
void put_number(std::string& s, double v) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  s.append(buf, end);
}

// One CSV row; a non-finite value is refused (never written as nan or inf). The text is built in
// one string (no stream: a stream's sentry and virtual write per cell cost as much as to_chars).
struct Row {
  std::string& s;
  const std::vector<std::string>& labels;
  double t;
  std::size_t col = 0;
  void put(double v) {
    if (!std::isfinite(v)) {
      std::ostringstream m;
      m << "CSV: '" << labels[col] << "' is not finite (" << v << ") at t = " << t
        << " s: refusing to write it";
      throw Error(m.str(), labels[col], t);
    }
    if (col++) s += ',';
    put_number(s, v);
  }
  void put_row(const MatrixXd& x, int k) {
    for (int j = 0; j < x.cols(); ++j) put(x(k, j));
  }
};

void common_row(Row& row, const Trajectory& r, int k) {
  row.put(r.time[k]);
  row.put_row(r.q0, k);
  row.put_row(r.q1, k);
  row.put_row(r.a1, k);
  row.put_row(r.efforts, k);
  row.put_row(r.reactions, k);
}

std::string csv_text(const std::vector<std::string>& labels, std::span<const std::string> units,
                     int rows, const std::function<void(Row&, int)>& fill, const VectorXd& time) {
  if (!units.empty() && units.size() != labels.size())
    throw Error("CSV: " + std::to_string(units.size()) + " units for " +
                std::to_string(labels.size()) + " columns");
  std::string s;
  s.reserve(static_cast<std::size_t>(rows + 2) * labels.size() * 24);  // 24: a typical cell
  auto line = [&s](const auto& cells) {
    for (std::size_t j = 0; j < cells.size(); ++j) {
      if (j) s += ',';
      s += cells[j];
    }
    s += '\n';
  };
  line(labels);
  if (!units.empty()) line(units);
  for (int k = 0; k < rows; ++k) {
    Row row{s, labels, time[k]};
    fill(row, k);
    s += '\n';
  }
  return s;
}

}  // namespace

std::vector<std::string> trajectory_csv_labels(const Trajectory& r) {
  std::vector<std::string> labels = common_labels(r);
  if (r.has_energies())
    for (const char* l : {"energy.kinetic", "energy.potential", "work.inputs", "energy.dissipated",
                          "work.loads", "work.constraints"})
      labels.push_back(l);
  labels.insert(labels.end(), r.residual_labels.begin(), r.residual_labels.end());
  labels.insert(labels.end(), r.output_labels.begin(), r.output_labels.end());
  return labels;
}

std::string trajectory_csv(const Trajectory& r, std::span<const std::string> units) {
  return csv_text(
      trajectory_csv_labels(r), units, static_cast<int>(r.time.size()),
      [&](Row& row, int k) {
        common_row(row, r, k);
        if (r.has_energies())
          for (double v : {r.kinetic[k], r.potential[k], r.input_work[k], r.dissipated[k],
                           r.load_work[k], r.constraint_work[k]})
            row.put(v);
        row.put_row(r.residuals, k);
        if (!r.output_labels.empty()) row.put_row(r.outputs, k);
      },
      r.time);
}

void write_trajectory_csv(const Trajectory& r, const std::string& path) {
  write_file_atomically(path, trajectory_csv(r));
}

}  // namespace mo2d
