// The path tracer with 1 and 4 lanes (--wavelengths), apart from the 8-lane default (path_integrator_impl.h).
#include "core/render/path_integrator_impl.h"

namespace prism {

PRISM_INSTANTIATE_PATH_RADIANCE(1)
PRISM_INSTANTIATE_PATH_RADIANCE(4)

}  // namespace prism
