// golden: eval --at 0.25,0.5 --at 0.5,0.5 --at 0.75,0.125
// noise, pnoise and cellnoise at points, in 1 to 4 dimensions, float and point results.
displacement t() {
    float a = noise(u * 3) + noise(u * 3, v * 3) + noise(P * 3) + noise(P * 3, v);
    float b = pnoise(u * 8, 4) + cellnoise(P * 4);
    point c = noise(P * 2);
    P += (a, b, xcomp(c) + ycomp(c) + zcomp(c));
}
