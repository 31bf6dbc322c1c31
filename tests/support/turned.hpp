// A surface turned off the octree's axes, as a user's mesh lies: about the z axis, then about the
// x axis, both through the origin.
#pragma once

#include <cmath>

#include "slc/geometry/surface.hpp"

namespace slc::test_support {

inline Surface turned(Surface s, double about_z, double about_x) {
    const double cz = std::cos(about_z), sz = std::sin(about_z);
    const double cx = std::cos(about_x), sx = std::sin(about_x);
    for (Vec3& v : s.vertices) {
        v = {cz * v.x - sz * v.y, sz * v.x + cz * v.y, v.z};
        v = {v.x, cx * v.y - sx * v.z, sx * v.y + cx * v.z};
    }
    return s;
}

}  // namespace slc::test_support
