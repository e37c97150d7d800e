// The path tracer with 8 lanes, the default (path_integrator_impl.h), alone in its file.
#include "core/render/path_integrator_impl.h"

namespace prism {

PRISM_INSTANTIATE_PATH_RADIANCE(8)

}  // namespace prism
