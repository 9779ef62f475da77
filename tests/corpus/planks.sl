/*
 * planks.sl: a wooden floor of staggered planks: grooves at the plank ends and sides by
 * filterstep, each plank at its own cellnoise height. Constructs: filterstep, floor, cellnoise of
 * two floats, a uniform float computed from parameters.
 */
displacement planks(float Km = 0.01, plankwidth = 0.1, planklength = 0.6, groove = 0.004)
{
    uniform float gw = groove / plankwidth;
    float row = floor(t / plankwidth);
    float ss = s / planklength + 0.37 * row;
    float col = floor(ss);
    float fs = (ss - col) * planklength / plankwidth;
    float ft = t / plankwidth - row;
    float side = filterstep(gw, ft) * (1 - filterstep(1 - gw, ft));
    float ends = filterstep(gw, fs) * (1 - filterstep(planklength / plankwidth - gw, fs));
    float lift = 0.3 * float cellnoise(col, row);
    P += Km * (side * ends * (1 + lift) - 1) * normalize(N);
    N = calculatenormal(P);
}
