// CSV numbers in the shortest round-trip form and the unit of every column (mo2d/csv.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

using namespace mo2d;

namespace {

std::vector<std::vector<std::string>> cells(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::istringstream l(line);
    for (std::string c; std::getline(l, c, ',');) row.push_back(c);
    rows.push_back(row);
  }
  return rows;
}

// The values trajectory_csv writes, row by row, in the order of its columns.
std::vector<double> row_values(const Trajectory& r, int k) {
  std::vector<double> v{r.time[k]};
  for (const Eigen::MatrixXd* x : {&r.q0, &r.q1, &r.a1, &r.efforts, &r.reactions})
    for (int j = 0; j < x->cols(); ++j) v.push_back((*x)(k, j));
  if (r.has_energies())
    for (double e : {r.kinetic[k], r.potential[k], r.input_work[k], r.dissipated[k], r.load_work[k],
                     r.constraint_work[k]})
      v.push_back(e);
  for (int j = 0; j < r.residuals.cols(); ++j) v.push_back(r.residuals(k, j));
  for (int j = 0; j < r.outputs.cols(); ++j) v.push_back(r.outputs(k, j));
  return v;
}

std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

}  // namespace

// strtod of every cell gives back the double written, bit for bit; and no cell is longer than
// the shortest such text (17 significant digits would write 0.005 as 0.0050000000000000001).
TEST(CsvNumbers, EveryCellReadsBackBitIdentical) {
  const Model m = build_model(mechanisms::double_fourbar());
  ForwardOptions o;
  o.t1 = 0.5;
  o.samples = 21;
  const Trajectory r = forward_dynamics(m, consistent_state(m, {{}, {{"crank0.w", -1.0}}}), o);
  const auto rows = cells(trajectory_csv(r));
  ASSERT_EQ(rows.size(), 22u);
  int checked = 0;
  for (int k = 0; k < 21; ++k) {
    const std::vector<double> want = row_values(r, k);
    ASSERT_EQ(rows[k + 1].size(), want.size());
    for (std::size_t j = 0; j < want.size(); ++j) {
      const std::string& cell = rows[k + 1][j];
      char* end = nullptr;
      const double got = std::strtod(cell.c_str(), &end);
      ASSERT_EQ(*end, '\0') << cell;
      EXPECT_EQ(bits(got), bits(want[j])) << rows[0][j] << " at row " << k << ": " << cell;
      char shortest[32];
      std::snprintf(shortest, sizeof shortest, "%.17g", want[j]);
      EXPECT_LE(cell.size(), std::strlen(shortest)) << cell;
      ++checked;
    }
  }
  EXPECT_GT(checked, 21 * 30);
  EXPECT_EQ(rows[2][0], "0.025");  // t = 0.5 / 20, not 0.025000000000000001
}

TEST(CsvNumbers, ShortestFormOfKnownValues) {
  const Model m = build_model(mechanisms::pendulum().system);
  Trajectory r =
      inverse_dynamics(m, mechanisms::pendulum().motion, {.t0 = 0, .t1 = 0.01, .samples = 3});
  r.time << 0.1 + 0.2, 0.005, 1e-300;
  const auto rows = cells(trajectory_csv(r));
  EXPECT_EQ(rows[1][0], "0.30000000000000004");
  EXPECT_EQ(rows[2][0], "0.005");
  EXPECT_EQ(rows[3][0], "1e-300");
}

TEST(CsvUnits, PendulumColumnsHaveTheUnitsOfTheirKind) {
  const mechanisms::Example ex = mechanisms::pendulum();
  const Model m = build_model(ex.system);
  const Trajectory r = inverse_dynamics(m, ex.motion, {.t0 = 0, .t1 = 0.1, .samples = 3});
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  const std::vector<std::string> units = trajectory_csv_units(m, r);
  ASSERT_EQ(labels.size(), units.size());
  auto unit = [&](const std::string& label) {
    for (std::size_t k = 0; k < labels.size(); ++k)
      if (labels[k] == label) return units[k];
    ADD_FAILURE() << "no column " << label;
    return std::string("?");
  };
  EXPECT_EQ(unit("t"), "s");
  EXPECT_EQ(unit("link.P.x"), "m");
  EXPECT_EQ(unit("link.angle"), "rad");  // extra coordinate of the rotation rate link.w
  EXPECT_EQ(unit("link.angle.rate"), "rad/s");
  EXPECT_EQ(unit("link.w"), "rad/s");
  EXPECT_EQ(unit("link.w.dot"), "rad/s²");
  EXPECT_EQ(unit("link.P.vx.dot"), "m/s²");
  EXPECT_EQ(unit("pivot.torque"), "N·m");
  EXPECT_EQ(unit("pivot.Fx"), "N");
  EXPECT_EQ(unit("residual.position"), "");  // rows of different units
  // the units row: the second line of the CSV
  const auto rows = cells(trajectory_csv(r, units));
  EXPECT_EQ(rows[0], labels);
  EXPECT_EQ(rows[1][0], "s");
  EXPECT_EQ(rows.size(), 5u);
  EXPECT_THROW(trajectory_csv(r, std::vector<std::string>{"s"}), Error);
}

TEST(CsvUnits, SlidersLoadsAndEnergies) {
  const Scene s = load_scene(std::string(MO2D_MECHANISMS_DIR) + "/crank_press.yaml");
  const Model m = build_scene_model(s);
  InverseOptions o = inverse_options(s);
  o.t1 = o.t0 + 0.05;
  o.samples = 3;
  Trajectory r = inverse_dynamics(m, s.motion, o);
  add_output_columns(m, r, s.outputs);
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  const std::vector<std::string> units = trajectory_csv_units(m, r);
  ASSERT_EQ(labels.size(), units.size());
  int springs = 0, powers = 0, energies = 0, unknown = 0;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    const std::string& l = labels[k];
    auto ends = [&](const std::string& x) {
      return l.size() > x.size() && l.compare(l.size() - x.size(), x.size(), x) == 0;
    };
    // the unit each kind of column must have (none of them: nothing to check)
    std::string want = "-";
    int* count = nullptr;
    if (ends(".tension")) want = "N", count = &springs;
    if (ends(".power")) want = "W", count = &powers;
    if (l.starts_with("energy.") || l.starts_with("work.")) want = "J", count = &energies;
    if (ends(".q")) want = "m";
    if (ends(".force")) want = "N";
    if (want != "-") {
      EXPECT_EQ(units[k], want) << l;
      if (count) ++*count;
    }
    if (units[k].empty() && !l.starts_with("residual.")) ++unknown;
  }
  EXPECT_GT(springs, 0);
  EXPECT_GT(powers, 0);
  EXPECT_EQ(energies, 0);  // an inverse run
  EXPECT_EQ(unknown, 0);   // every column of this scene has a unit
}

TEST(CsvUnits, ForwardEnergiesInJoules) {
  const Model m = build_model(mechanisms::double_fourbar());
  ForwardOptions o;
  o.t1 = 0.01;
  o.samples = 2;
  const Trajectory r = forward_dynamics(m, consistent_state(m, {{}, {{"crank0.w", -1.0}}}), o);
  const std::vector<std::string> labels = trajectory_csv_labels(r);
  const std::vector<std::string> units = trajectory_csv_units(m, r);
  int joules = 0;
  for (std::size_t k = 0; k < labels.size(); ++k) {
    if (!labels[k].starts_with("energy.") && !labels[k].starts_with("work.")) continue;
    EXPECT_EQ(units[k], "J") << labels[k];
    ++joules;
  }
  EXPECT_EQ(joules, 6);
}
