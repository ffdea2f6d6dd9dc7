#pragma once
#include "glint/math/vector.h"

namespace glint {

/// A point sampled uniformly by area on a shape, with the shape's unit normal there. The
/// density with respect to area is 1 / area() of the shape.
struct AreaSample {
    Point3 p;
    Normal3 n;
};

}  // namespace glint
