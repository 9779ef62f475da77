// tests/tools/check_layers/tools/main.cpp: the command line, at the top, includes any library.
#include "compiler/compile.h"
#include "image/png_writer.h"
#include "rib/rib.h"
#include "texture/texture.h"
