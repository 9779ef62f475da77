/*
 * golfball.sl: golf-ball dimples on a staggered grid: spherical caps pressed in where a point is
 * within the dimple radius of its cell centre. Constructs: floor and mod on alternate rows, a
 * point cast with a space, distance, a clamped sqrt profile, step.
 */
displacement golfball(float Km = 0.015, density = 10, radius = 0.4)
{
    float row = floor(t * density);
    float ss = s * density + (mod(row, 2) == 1 ? 0.5 : 0);
    point here = point(ss, t * density, 0);
    point centre = point(floor(ss) + 0.5, row + 0.5, 0);
    float d = distance(here, centre);
    float cap = step(d, radius) * (1 - (d / radius) * (d / radius));
    P -= Km * cap * normalize(N);
    N = calculatenormal(P);
}
