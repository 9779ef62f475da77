// tests/tools/check_layers/rib/rib.cpp: the one exception, rib/ including the renderer's scene
// description, is allowed.
#include "rib/rib.h"

#include "renderer/geometry/bvh.h"
#include "renderer/scene.h"
