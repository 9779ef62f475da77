// tests/tools/check_layers/texture/texture_file.cpp: texture/ includes image/ and a file beside
// it, but not the scene description above it (however the directive is spaced).
#include <vector>

#include "image/image_io.h"
#include "texture_impl.h"
// clang-format off
#  include   "scene/scene.h"  // crosses the layers
// clang-format on
