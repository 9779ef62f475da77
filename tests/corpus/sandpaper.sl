/*
 * sandpaper.sl: grit on paper: a point assembled component by component with setxcomp and
 * friends (declared, then filled in, as much real code does), fed to cellnoise-jittered grains.
 * Constructs: a point declared without initialiser then set by setxcomp/setycomp/setzcomp,
 * cellnoise, distance, max.
 */
displacement sandpaper(float Km = 0.004, frequency = 60, grain = 0.4)
{
    point Q;
    setxcomp(Q, s * frequency);
    setycomp(Q, t * frequency);
    setzcomp(Q, 0);
    point cell = point(floor(xcomp(Q)), floor(ycomp(Q)), 0);
    vector jit = vector cellnoise(cell);
    point centre = cell + vector(0.5 + 0.3 * (xcomp(jit) - 0.5), 0.5 + 0.3 * (ycomp(jit) - 0.5), 0);
    float d = distance(Q, centre);
    P += Km * max(0, 1 - d / grain) * zcomp(jit) * normalize(N);
    N = calculatenormal(P);
}
