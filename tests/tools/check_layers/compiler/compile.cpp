// tests/tools/check_layers/compiler/compile.cpp: compiler/ includes lang/ and vm/, and what vm/
// links (vm/numbers/), but not the renderer that uses it.
#include "compiler/compile.h"

#include "lang/ast.h"
#include "renderer/render.h"  // crosses the layers
#include "vm/numbers/affine.h"
#include "vm/program.h"
