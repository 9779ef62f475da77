// tests/tools/check_layers/renderer/render.h: the renderer includes the scene description it
// renders, the image library and the compiler.
#pragma once

#include "compiler/compile.h"
#include "image/exr_writer.h"
#include "scene/geometry/surface.h"
