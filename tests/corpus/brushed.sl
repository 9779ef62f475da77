/*
 * brushed.sl: brushed metal: fine grooves along the surface's v direction, their phase jittered
 * across u by 1-D noise; the groove direction is found from dPdv and N with cross products.
 * Constructs: dPdv, the cross product ^, the dot product ., u and v, length, normalize of a
 * vector, noise of a float.
 */
displacement brushed(float Km = 0.002, grooves = 150)
{
    normal Nn = normalize(N);
    vector along = normalize(dPdv);
    vector across = Nn ^ along;
    float lean = along . Nn;   /* 0 on a regular surface */
    float g = sin(2 * PI * (u * grooves + 4 * float noise(u * 40)));
    float depth = 0.5 + 0.5 * float noise(u * 200, v * 10);
    P += Km * (g * depth + lean) * Nn + 0 * length(across) * Nn;
    N = calculatenormal(P);
}
