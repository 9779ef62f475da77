// golden: compile
// A directive made by a macro reaches the lexer after preprocessing, which cannot run it.
#define HASH #
HASH include "x.h"
displacement t() {
    P += N;
}
