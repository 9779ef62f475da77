// scene/geometry/surface.cpp: the surface setters of surface.h compiled for the VM's number types
// (its AFFRAY_SURFACE_INSTANCES says why).
#include "scene/geometry/surface.h"

namespace affray::renderer {

AFFRAY_SURFACE_NUMBER_TYPES(AFFRAY_SURFACE_INSTANCES, )

}  // namespace affray::renderer
