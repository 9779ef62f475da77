// golden: compile
// A literal past the largest double is an error; one that underflows is just 0.
displacement t() {
    P += 1e999 * N;
    P += 1e-999 * N;
}
