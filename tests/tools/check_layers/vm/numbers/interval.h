// tests/tools/check_layers/vm/numbers/interval.h: a library in a subfolder of another is a layer of
// its own, below its parent: it may not include the parent.
#pragma once

#include "vm/numbers/rounding.h"
#include "vm/program.h"  // crosses the layers
