/*
 * twist.sl: straight ridges whose direction turns as t goes from 0 to 1, like a fan of grooves
 * twisted about the patch centre, fading out towards the edges. Each point is carried into the
 * ridges' own frame by a matrix built from a rotation whose angle varies over the surface and a
 * placement the scene may set. Exercises matrix values: rotate, translate, products, 1/m,
 * determinant, transform and comp.
 *
 *   Km          ridge height
 *   frequency   ridges per unit length across them
 *   turns       full turns of the ridge direction from t = 0 to t = 1
 *   place       an extra transform of the pattern (row-vector matrix, 16 numbers)
 */
displacement twist(float Km = 0.03, frequency = 6, turns = 0.25; matrix place = 1)
{
    matrix centre = translate(matrix 1, vector(-0.5, -0.5, 0));
    matrix spin = rotate(matrix 1, 2 * PI * turns * t, vector(0, 0, 1));
    matrix frame = centre * spin * place;
    point q = transform(frame, point(s, t, 0));
    /* Back to (s, t) through the inverse: the fade is measured on the surface, not in the
       turned frame. */
    point home = transform(1 / frame, q);
    float fade = 1 - smoothstep(0.3, 0.5, distance(home, point(0.5, 0.5, 0)));
    /* The determinant is the frame's area scale (1 unless `place` scales): the ridges keep
       their height per unit of the pattern. */
    float area = abs(determinant(frame));
    float across = xcomp(q) + comp(frame, 3, 2);
    P += Km * fade * sin(2 * PI * frequency * across) / max(area, 1e-3) * normalize(N);
    N = calculatenormal(P);
}
