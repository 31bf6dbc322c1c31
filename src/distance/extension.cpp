// The extensions are templates (extension.hpp); this file instantiates them for the value types
// the library uses, so that errors in them show up when the library is built.
#include "slc/distance/extension.hpp"

namespace slc {

template class WhitneyExtension<double>;
template class WhitneyExtension<Vec2>;

}  // namespace slc
