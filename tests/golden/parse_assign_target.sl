// golden: compile
// Only a variable or an array element can be assigned.
displacement t() {
    u + 1 = 2;
    noise(u) = 2;
    P += N;
}
