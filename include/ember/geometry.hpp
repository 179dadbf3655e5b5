#pragma once
// Plane-based exact geometry: planes, homogeneous points, convex polygons,
// clipping and line/segment intersection. Conventions: docs/geometry.md.
#include "ember/geometry/bounds.hpp"
#include "ember/geometry/clip.hpp"
#include "ember/geometry/intersect.hpp"
#include "ember/geometry/plane.hpp"
#include "ember/geometry/point.hpp"
#include "ember/geometry/polygon.hpp"
#include "ember/geometry/axis_line.hpp"
