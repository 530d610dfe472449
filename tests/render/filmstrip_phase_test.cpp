// Filmstrips by phase (FilmstripOptions::phase, cycle): the tiles are the samples nearest evenly
// spaced phase values over the run's last cycle, worked out here by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mo2d/mechanisms.hpp"
#include "mo2d/mo2d.hpp"
#include "mo2d/render.hpp"

namespace {

using namespace mo2d;

TEST(RenderFilmstripPhase, TilesAreTheSamplesNearestEvenPhasesOfTheLastCycle) {
  const mechanisms::Example ex = mechanisms::whitworth();
  const Model m = build_model(ex.system);
  InverseOptions run = ex.run;
  run.samples = 101;
  const Motion mo = motion_of(inverse_dynamics(m, ex.motion, run));
  FilmstripOptions by_phase;
  by_phase.frames = 4;
  by_phase.columns = 4;
  by_phase.tile.width = 120, by_phase.tile.height = 90;
  for (int k = 0; k < 101; ++k) by_phase.phase.push_back(0.37 * k);  // a fast phase: 37 rad in all
  by_phase.cycle = 2 * std::numbers::pi;
  FilmstripOptions by_hand = by_phase;
  by_hand.phase.clear();
  for (int j = 0; j < 4; ++j)  // targets 37 - 2 pi + j pi / 2, nearest samples of 0.37 k
    by_hand.samples.push_back(static_cast<int>(
        std::lround((37 - 2 * std::numbers::pi + j * std::numbers::pi / 2) / 0.37)));
  EXPECT_EQ(by_hand.samples, (std::vector<int>{83, 87, 92, 96}));
  EXPECT_EQ(render_filmstrip(m, mo, by_phase).argb, render_filmstrip(m, mo, by_hand).argb);
  // decreasing phases work the same way
  for (double& p : by_phase.phase) p = -p;
  EXPECT_EQ(render_filmstrip(m, mo, by_phase).argb, render_filmstrip(m, mo, by_hand).argb);
  by_phase.cycle = 40;  // more than the run covers
  EXPECT_THROW(render_filmstrip(m, mo, by_phase), Error);
  by_phase.cycle = 1;
  by_phase.phase.pop_back();
  EXPECT_THROW(render_filmstrip(m, mo, by_phase), Error);
}

}  // namespace
