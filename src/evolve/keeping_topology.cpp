// The notes of keeping_topology's choice of thin depth.
#include "slc/evolve/keeping_topology.hpp"

#include <fmt/format.h>

namespace slc {

std::optional<std::string> thin_depth_note(std::string_view what, int asked, int kept,
                                           std::string_view setting) {
    if (kept < asked) {
        return fmt::format(
            "the contour of the {} at {} {} has parts, holes or handles it does not have (thin "
            "cells following a sharp edge or point catch it unevenly); kept {} {}, which has none",
            what, setting, asked, setting, kept);
    }
    if (kept > asked) {
        return fmt::format(
            "a part of the {} is thinner than the contours resolve at {} {}; the thin cells went "
            "{} levels deep to keep it",
            what, setting, asked, kept);
    }
    return std::nullopt;
}

}  // namespace slc
