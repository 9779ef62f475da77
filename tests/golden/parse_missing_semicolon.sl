// golden: compile
// Bison's message names the token found and the one expected.
displacement t() {
    float k = 2
    P += k * N;
}
