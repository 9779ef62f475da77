/*
 * basketweave.sl: a plain weave: warp and weft threads alternate over and under on a checkerboard
 * of cells, each thread a rounded ridge across its cell. Constructs: the header's whichtile,
 * even and repeat, a varying if/else choosing the direction, sin.
 */
#include "patterns.h"

displacement basketweave(float Km = 0.015, frequency = 12, strands = 3)
{
    float cs = whichtile(s, frequency), ct = whichtile(t, frequency);
    float fs = repeat(s, frequency), ft = repeat(t, frequency);
    float h;
    if (even(cs + ct))
        h = abs(sin(PI * ft * strands)) * sin(PI * fs);
    else
        h = abs(sin(PI * fs * strands)) * sin(PI * ft);
    P += Km * h * normalize(N);
    N = calculatenormal(P);
}
