#pragma once
// Plane-based exact geometry: planes, homogeneous points, convex polygons,
// clipping and line/segment intersection. Conventions: docs/geometry.md.
#include "geometry/bounds.hpp"
#include "geometry/clip.hpp"
#include "geometry/intersect.hpp"
#include "geometry/plane.hpp"
#include "geometry/point.hpp"
#include "geometry/polygon.hpp"
#include "geometry/axis_line.hpp"
