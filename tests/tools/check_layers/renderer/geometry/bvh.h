// tests/tools/check_layers/renderer/geometry/bvh.h: a subfolder that is no library of its own is
// its folder's: renderer/geometry/ includes renderer/ and image/, but no folder that is not a
// library, such as fuzz/.
#pragma once

#include "fuzz/fuzz_util.h"  // crosses the layers
#include "image/exr_writer.h"
#include "renderer/scene.h"
