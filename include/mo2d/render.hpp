#pragma once
// mo2d rendering (target mo2d::render, links Cairo): frames, filmstrips, plots,
// animations (FFmpeg). See
// docs/rendering.md.
#include "mo2d/render/animate.hpp"
#include "mo2d/render/frame.hpp"
#include "mo2d/render/image.hpp"
#include "mo2d/render/plot.hpp"
#include "mo2d/render/run.hpp"
