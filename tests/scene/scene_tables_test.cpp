// Tables in scene files: a motion from a table that samples a cubic exactly gives the results of
// the closed-form motion; the shipped cam (mechanisms/cam_table.yaml, a table inside a user
// constraint) against the power balance of a second formulation; and the errors, located.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "mo2d/mo2d.hpp"
#include "mo2d/scene.hpp"

namespace mo2d {
namespace {

using std::numbers::pi;

class SceneTables : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mo2d_scene_tables_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir / "data"); }
  void TearDown() override { std::filesystem::remove_all(dir); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
  }
  Scene parse(const std::string& text) { return parse_scene(text, (dir / "s.yaml").string()); }
  std::string error(const std::string& text) {
    try {
      parse(text);
    } catch (const SceneError& e) {
      std::string w = e.what();
      for (auto p = w.find(dir.string() + "/"); p != std::string::npos;
           p = w.find(dir.string() + "/"))
        w.erase(p, dir.string().size() + 1);
      return w;
    }
    return "no error";
  }
};

// A crank driven by theta(t) = 2t + 0.5t^2 - 0.1t^3, a slider-crank under gravity.
std::string slider_crank(const std::string& motion, const std::string& tables = "") {
  return tables + R"yaml(
parameters: {r: 0.1, L: 0.35, e: 0.03, xb: r + sqrt(L^2 - e^2)}
ground: {O: [0, 0], R1: [0, e], R2: [1, e]}
bodies:
  crank: {nodes: {O: [0, 0], A: [r, 0]}, mass: 0.5, inertia: 0.0005, com: {between: [O, A]}}
  rod: {nodes: {A: [r, 0], B: [xb, e]}, mass: 0.3, inertia: 0.003, com: {between: [A, B]}}
  slider: {nodes: {B: [xb, e]}, mass: 1}
joints:
  pivot: {type: revolute, node_a: ground.O, node_b: crank.O, actuated: true}
  pin: {type: revolute, node_a: crank.A, node_b: rod.A}
  wrist: {type: revolute, node_a: rod.B, node_b: slider.B}
  rail: {type: prismatic, axis_from: ground.R1, axis_to: ground.R2, slider: slider.B}
coordinates: {crank.angle: {rate: {crank.w: 1}}}
loads: {gravity: [0, -9.81]}
motion: {crank.angle: )yaml" +
         motion + R"yaml(}
run: {duration: 2, samples: 81}
)yaml";
}

double theta(double t) {
  return 2 * t + 0.5 * t * t - 0.1 * t * t * t;
}

TEST_F(SceneTables, MotionFromATableOfACubicEqualsTheClosedForm) {
  // uneven times, in ms, over [0, 2] s: the not-a-knot spline is the cubic itself
  std::string csv = "time_ms, other, angle\n";
  for (double t : {0.0, 0.13, 0.4, 0.55, 0.9, 1.2, 1.25, 1.7, 2.0}) {
    char line[100];
    std::snprintf(line, sizeof line, "%.17g, 7, %.17g\n", t * 1000, theta(t));
    csv += line;
  }
  write("data/theta.csv", csv);
  const Scene table = parse(slider_crank(
      "th(t)", "tables: {th: {file: data/theta.csv, x: time_ms, y: angle, scale_x: 1e-3}}\n"));
  const Scene closed = parse(slider_crank("2*t + 0.5*t^2 - 0.1*t^3"));
  const Model ma = build_scene_model(table), mb = build_scene_model(closed);
  const Trajectory a = inverse_dynamics(ma, table.motion, inverse_options(table));
  const Trajectory b = inverse_dynamics(mb, closed.motion, inverse_options(closed));
  ASSERT_EQ(a.time.size(), 81);
  const int th = a.column("crank.angle");
  EXPECT_NEAR(a.q0(80, th), theta(2), 1e-13);
  // round-off of the spline's coefficients only (1 ms = 1e-3 s rescaled)
  EXPECT_LE((a.q0 - b.q0).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LE((a.q1 - b.q1).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LE((a.a1 - b.a1).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE((a.efforts - b.efforts).cwiseAbs().maxCoeff(), 1e-10 * b.efforts.cwiseAbs().maxCoeff());
}

TEST_F(SceneTables, ShippedCamAgainstThePowerBalance) {
  const std::string path = std::string(MO2D_MECHANISMS_DIR) + "/cam_table.yaml";
  const Scene scene = load_scene(path);
  const Model model = build_scene_model(scene);
  EXPECT_EQ(model.dof, 1);
  const Trajectory r = inverse_dynamics(model, scene.motion, inverse_options(scene));
  // the same table in C++
  const LookupTable lift =
      read_table_csv(std::string(MO2D_MECHANISMS_DIR) + "/cam_lift.csv", "lift",
                     {.x = "angle_deg", .y = "lift_mm", .scale_x = pi / 180, .scale_y = 1e-3},
                     {Interpolation::cubic, Extrapolation::periodic});
  const double omega = 2 * pi, m = 0.5, g = 9.81;
  const int th = r.column("cam.angle"), y = r.column("follower.P.y");
  const int u = r.effort("cam_shaft.torque");
  double worst = 0, largest = 0;
  for (int k = 0; k < r.time.size(); ++k) {
    const double angle = r.q0(k, th);
    EXPECT_NEAR(angle, omega * r.time(k), 1e-12);
    const Jet s = lift(Jet(angle, omega, 0));  // y' and y'' along time
    EXPECT_NEAR(r.q0(k, y), 0.04 + s.v, 1e-12);
    // torque * omega = m (y'' + g) y'
    const double expected = m * (s.dd + g) * s.d / omega;
    worst = std::max(worst, std::abs(r.efforts(k, u) - expected));
    largest = std::max(largest, std::abs(expected));
  }
  // N m: a real load (the cycloidal rise alone needs m g y'max = 0.5 * 9.81 * 0.0191 = 0.094)
  EXPECT_GT(largest, 0.09);
  EXPECT_LE(worst, 1e-10 * largest) << "worst " << worst << " of " << largest;
}

TEST_F(SceneTables, TablesAreUsableInConstantsAndSubsystems) {
  write("c.csv", "x, y\n0, 1\n1, 3\n2, 2\n3, 5\n");
  const Scene s =
      parse(slider_crank("c(t) - c(0)",
                         "tables: {c: {file: c.csv, interpolation: linear, extrapolate: clamp}}\n"
                         "initial: {velocities: {crank.w: c(0.5)}}\n"));
  ASSERT_EQ(s.initial.velocities.size(), 1u);
  EXPECT_EQ(s.initial.velocities[0].second, 2);  // linear: halfway between 1 and 3
  EXPECT_EQ(s.motion[0].motion(Jet(2.5)).v, 3.5 - 1);
  EXPECT_EQ(s.motion[0].motion(Jet(9, 1, 0)).v, 5 - 1);  // clamped
}

TEST_F(SceneTables, Errors) {
  write("c.csv", "x, y\n0, 1\n1, 3\n2, 2\n3, 5\n");
  write("bad.csv", "angle, lift\n0, 0\n10, 1\n10, 2\n");
  auto with = [](const std::string& tables, const std::string& motion = "c(t)") {
    return slider_crank(motion, tables);
  };
  EXPECT_EQ(error(with("tables: {c: {file: c.csv, extrapolat: clamp}}")),
            "s.yaml:1:27: table 'c': unknown key 'extrapolat' (did you mean 'extrapolate'?); "
            "expected one of: file, x, y, interpolation, extrapolate, scale_x, scale_y");
  EXPECT_EQ(error(with("tables: {c: {file: c.csv, extrapolate: periodc}}")),
            "s.yaml:1:40: table 'c'.extrapolate: unknown value 'periodc' (did you mean "
            "'periodic'?); expected one of: error, clamp, periodic");
  EXPECT_EQ(error(with("tables: {mod: {file: c.csv}}")),
            "s.yaml:1:10: table 'mod': a table name is a letter or '_' followed by letters, "
            "digits or '_', and not t, pi or a function name");
  EXPECT_EQ(error(with("tables: {r: {file: c.csv}}")),
            "s.yaml:1:10: table 'r': a parameter has the same name");
  EXPECT_EQ(error(with("tables: {c: {x: x}}")),
            "s.yaml:1:13: table 'c': missing required key 'file'");
  EXPECT_EQ(error(with("tables: {c: {file: none.csv}}")),
            "s.yaml:1:20: none.csv: table 'c': cannot open the file");
  EXPECT_EQ(error(with("tables: {c: {file: bad.csv}}")),
            "s.yaml:1:20: bad.csv:4: table 'c': x must increase: angle = 10 after 10 on line 3");
  EXPECT_EQ(error(with("tables: {c: {file: c.csv, scale_x: -1}}")),
            "s.yaml:1:36: table 'c'.scale_x: must be > 0 (x must keep increasing)");
  // in expressions: the column of the call
  EXPECT_EQ(error(with("tables: {c: {file: c.csv}}", "2 * cc(t)")),
            "s.yaml:15:27: motion.crank.angle: in expression '2 * cc(t)': unknown function 'cc' "
            "(did you mean 'c'?)");
  EXPECT_EQ(error(with("tables: {c: {file: c.csv}}", "\"c(t, 1)\"")),
            "s.yaml:15:24: motion.crank.angle: in expression 'c(t, 1)': c() takes 1 argument, "
            "got 2");
  // parameters are read before the tables
  EXPECT_EQ(error("tables: {c: {file: c.csv}}\nparameters: {p: 2 * c(1)}\n"),
            "s.yaml:2:17: parameter 'p': table 'c' is used in a parameter: parameters are "
            "constants evaluated before the tables are read; call the table where the value is "
            "used");
}

}  // namespace
}  // namespace mo2d
