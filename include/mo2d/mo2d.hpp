#pragma once
// mo2d: dynamics of planar mechanisms in Orsino's nodal formulation. Umbrella header.
#include "mo2d/budget.hpp"
#include "mo2d/csv.hpp"
#include "mo2d/dynamics.hpp"
#include "mo2d/error.hpp"
#include "mo2d/forward.hpp"
#include "mo2d/inverse.hpp"
#include "mo2d/jet.hpp"
#include "mo2d/kinematics.hpp"
#include "mo2d/model.hpp"
#include "mo2d/output.hpp"
#include "mo2d/system.hpp"
#include "mo2d/trajectory.hpp"
