// golden: compile
// A bad parameter list is skipped up to the body, which is still read.
displacement t(float Km = 1, 2) {
    P += Km * N;
}
