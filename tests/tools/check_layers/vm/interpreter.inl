// tests/tools/check_layers/vm/interpreter.inl: vm/ includes what it links: vm/numbers/, texture/
// and diag/.
#include "diag/diagnostic.h"
#include "texture/texture.h"
#include "vm/numbers/interval.h"
