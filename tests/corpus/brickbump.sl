/*
 * brickbump.sl: running-bond bricks with antialiased mortar grooves (the RenderMan Companion's
 * brick listing, displaced). Constructs: #define constants, mod, floor, odd rows through the
 * header's macros, filterwidth (Du, Dv, du, dv), the header's filteredpulse.
 */
#include "patterns.h"

#define BRICKWIDTH 0.25
#define BRICKHEIGHT 0.08
#define MORTARTHICKNESS 0.01
#define BMWIDTH (BRICKWIDTH + MORTARTHICKNESS)
#define BMHEIGHT (BRICKHEIGHT + MORTARTHICKNESS)
#define MWF (MORTARTHICKNESS * 0.5 / BMWIDTH)
#define MHF (MORTARTHICKNESS * 0.5 / BMHEIGHT)

displacement brickbump(float Km = 0.02)
{
    float ss = s / BMWIDTH, tt = t / BMHEIGHT;
    float swidth = filterwidth(ss), twidth = filterwidth(tt);
    if (odd(floor(tt)))
        ss += 0.5;
    float sbrick = floor(ss), tbrick = floor(tt);
    ss -= sbrick;
    tt -= tbrick;
    float w = filteredpulse(MWF, 1 - MWF, ss, swidth);
    float h = filteredpulse(MHF, 1 - MHF, tt, twidth);
    P += Km * (w * h - 1) * normalize(N);
    N = calculatenormal(P);
}
