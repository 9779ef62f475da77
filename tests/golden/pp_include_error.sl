// golden: compile
// An error inside an included file names that file and its line (paths shown relative to
// tests/golden by the golden driver), with its source line.
#include "include/bad_ripple.h"
displacement t() {
    P += ripple(u) * N;
}
