// golden: compile
// A condition is a comparison or a float ("!= 0", as in C).
displacement t() {
    if (P) P += N;
    while ("yes") P += N;
    P += P ? 1 : 2;
    P += !N;
}
