// golden: eval --mode affine --at 0.2,0.3 --at 0.7,0.9
// --at with a bounding mode bounds a region of one point: lo == hi.
displacement t() {
    P += 0.1 * sin(u * 6) * cos(v * 6) * N;
}
