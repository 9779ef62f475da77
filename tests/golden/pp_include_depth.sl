// golden: compile
// A header that includes itself twice would take 2^depth steps: past the include-depth limit
// (64) the preprocessor stops at once, with one error at the #include that went too deep.
#include "include/self_include.h"
displacement t() { P += 0.1 * N; }
