// golden: eval --at 0.5,0.5
// A shader may change N alone: P stays on the patch.
displacement t() {
    N = -N;
}
