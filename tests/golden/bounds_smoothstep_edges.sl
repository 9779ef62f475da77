// golden: eval --mode affine --region 0,1,0,1
// Issue 12: smoothstep whose edges come from cellnoise and may coincide: over several cells its
// division is by a range containing 0, and its clamp to [0, 1] keeps the bound finite.
displacement t() {
    float e0 = float cellnoise(floor(3 * u)), e1 = float cellnoise(floor(3 * u) + 7);
    P += smoothstep(e0, e1, v) * N;
}
