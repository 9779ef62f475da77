// golden: compile
// Letters or a second point glued to a number make one malformed token, reported once.
displacement t() {
    P += 1.5.2 * N;
    P += 3x * N;
    P += 2e * N;
}
