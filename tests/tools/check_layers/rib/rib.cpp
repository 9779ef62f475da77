// tests/tools/check_layers/rib/rib.cpp: rib/ builds the scene description (scene/) but does not
// reach the renderer that renders it.
#include "rib/rib.h"

#include "renderer/render.h"  // crosses the layers
#include "scene/geometry/surface.h"
#include "scene/scene.h"
