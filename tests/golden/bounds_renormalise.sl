// golden: eval --mode affine --region 0,1,0,1
// Issue 12: a vector renormalised in a loop stays bounded: normalize's components are clamped to
// [-1, 1] and the zero vector normalises to itself, so no turn can make it unbounded.
displacement t() {
    vector v = vector(1, 0, 0), w = vector(t - 0.5, 0.5 - s, s * t);
    float i;
    for (i = 0; i < 20; i += 1)
        v = normalize(v + w * (2 + sin(3 * s + i)));
    P += v;
}
