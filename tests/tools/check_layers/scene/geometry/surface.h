// tests/tools/check_layers/scene/geometry/surface.h: a subfolder that is no library of its own is
// its folder's: scene/geometry/ includes scene/ and vm/, but no folder that is not a library, such
// as fuzz/.
#pragma once

#include "fuzz/fuzz_util.h"  // crosses the layers
#include "scene/scene.h"
#include "vm/interpreter.h"
