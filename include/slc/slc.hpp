/// @file
/// The whole public interface of slc in one include, for programs that use most of it. Each
/// module's headers can also be included on their own (`include/slc/<module>/`).
#pragma once

#include "slc/contour/contour.hpp"
#include "slc/core/box.hpp"
#include "slc/core/error.hpp"
#include "slc/core/memory.hpp"
#include "slc/core/parallel.hpp"
#include "slc/core/vec2.hpp"
#include "slc/distance/distance_tree.hpp"
#include "slc/distance/extension.hpp"
#include "slc/evolve/defaults.hpp"
#include "slc/evolve/problems.hpp"
#include "slc/evolve/run.hpp"
#include "slc/evolve/self_convergence.hpp"
#include "slc/evolve/step.hpp"
#include "slc/evolve/study.hpp"
#include "slc/geometry/interface.hpp"
#include "slc/geometry/segment.hpp"
#include "slc/geometry/shapes.hpp"
#include "slc/geometry/validate.hpp"
#include "slc/geometry_modules/arclength.hpp"
#include "slc/geometry_modules/embedded.hpp"
#include "slc/geometry_modules/intrinsic.hpp"
#include "slc/io/interface_json.hpp"
#include "slc/io/plot.hpp"
#include "slc/io/render.hpp"
#include "slc/io/vtk.hpp"
#include "slc/velocity/expression.hpp"
#include "slc/velocity/factory.hpp"
#include "slc/velocity/grid_field.hpp"
#include "slc/velocity/laws.hpp"
#include "slc/velocity/velocity.hpp"

/// @namespace slc
/// Semi-Lagrangian contouring for moving interfaces, after Strain's paper of 2001 in the Journal
/// of Computational Physics. Signs as in DESIGN §2: signed distance F < 0 inside, outward normal N
/// = ∇F, curvature C = −∇·N; points move with dy/dt = u(y).
