// tests/tools/check_layers/image/exr_writer.cpp: image/ includes diag/; an include in a comment is
// no include, and a path that climbs out of the folder is refused whatever it names.
#include "image/exr_writer.h"

#include "../texture/texture.h"  // crosses the layers
#include "diag/diagnostic.h"

// #include "renderer/render.h" is what image/ may not do.
