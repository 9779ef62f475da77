// golden: eval --at 0.25,0.5 --at 0.75,0.5 -I include -D OCTAVES=2
// #include found through -I, function-like macros, #if/#elif on a -D value, __LINE__.
#include "waves.h"
#if OCTAVES > 2
#error too many octaves
#elif OCTAVES == 2
#define AMPLITUDE (WAVE(u, 1) + WAVE(u, 2))
#else
#define AMPLITUDE WAVE(u, 1)
#endif
displacement t() {
    P += AMPLITUDE * N + __LINE__ * 0 * N;
}
