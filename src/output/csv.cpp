// CSV writing (labels in the header, 17 significant digits, atomic replace).
#include "mo2d/csv.hpp"

#include <cmath>
#include <functional>
#include <sstream>
#include <vector>

#include "mo2d/error.hpp"
#include "output/write_file.hpp"

namespace mo2d {

namespace {

// Columns shared by inverse and forward results: t, coordinates, quasi-velocities, their
// derivatives (label + ".dot"), efforts, reactions.
template <class Result>
std::vector<std::string> common_labels(const Result& r) {
  std::vector<std::string> l{"t"};
  l.insert(l.end(), r.coordinate_labels.begin(), r.coordinate_labels.end());
  l.insert(l.end(), r.rate_labels.begin(), r.rate_labels.end());
  for (const auto& x : r.rate_labels) l.push_back(x + ".dot");
  l.insert(l.end(), r.input_labels.begin(), r.input_labels.end());
  l.insert(l.end(), r.reaction_labels.begin(), r.reaction_labels.end());
  return l;
}

// One CSV row; a non-finite value is refused (never written as nan or inf).
struct Row {
  std::ostringstream& s;
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
    s << (col++ ? "," : "") << v;
  }
  void put_row(const MatrixXd& x, int k) {
    for (int j = 0; j < x.cols(); ++j) put(x(k, j));
  }
};

template <class Result>
void common_row(Row& row, const Result& r, int k) {
  row.put(r.time[k]);
  row.put_row(r.q0, k);
  row.put_row(r.q1, k);
  row.put_row(r.a1, k);
  row.put_row(r.efforts, k);
  row.put_row(r.reactions, k);
}

std::string csv_text(const std::vector<std::string>& labels, int rows,
                     const std::function<void(Row&, int)>& fill, const VectorXd& time) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t j = 0; j < labels.size(); ++j) s << (j ? "," : "") << labels[j];
  s << "\n";
  for (int k = 0; k < rows; ++k) {
    Row row{s, labels, time[k]};
    fill(row, k);
    s << "\n";
  }
  return s.str();
}

}  // namespace

std::string inverse_csv(const InverseResult& r) {
  std::vector<std::string> labels = common_labels(r);
  for (const char* l : {"residual.position", "residual.velocity", "residual.acceleration"})
    labels.push_back(l);
  return csv_text(
      labels, static_cast<int>(r.time.size()),
      [&](Row& row, int k) {
        common_row(row, r, k);
        for (int j = 0; j < 3; ++j) row.put(r.residuals(k, j));
      },
      r.time);
}

std::string forward_csv(const ForwardResult& r) {
  std::vector<std::string> labels = common_labels(r);
  for (const char* l : {"energy.kinetic", "energy.potential", "work.inputs", "energy.dissipated",
                        "work.loads", "work.constraints", "residual.position", "residual.velocity"})
    labels.push_back(l);
  return csv_text(
      labels, static_cast<int>(r.time.size()),
      [&](Row& row, int k) {
        common_row(row, r, k);
        for (double v :
             {r.kinetic[k], r.potential[k], r.input_work[k], r.dissipated[k], r.load_work[k],
              r.constraint_work[k], r.residuals(k, 0), r.residuals(k, 1)})
          row.put(v);
      },
      r.time);
}

void write_forward_csv(const ForwardResult& r, const std::string& path) {
  write_file_atomically(path, forward_csv(r));
}

void write_inverse_csv(const InverseResult& r, const std::string& path) {
  write_file_atomically(path, inverse_csv(r));
}

}  // namespace mo2d
