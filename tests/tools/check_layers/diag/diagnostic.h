// tests/tools/check_layers/diag/diagnostic.h: the lowest layer, which includes only the standard library.
#pragma once

#include <string>
