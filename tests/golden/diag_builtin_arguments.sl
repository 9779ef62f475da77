// golden: compile
// Built-ins: overloads, argument counts, and the component functions.
displacement t() {
    matrix m = 1;
    P += min("a", 1);
    P += sqrt(1, 2);
    P += comp(P, 1, 2);
    P += comp(P, u);
    P += comp(m, 4, 0);
    P += comp(m, 1);
    float f = 1;
    P += comp(1, 0);
    setxcomp(f, 2);
    setxcomp(P, N);
    setycomp(P + 1, 2);
    setzcomp(Ng, 1);
}
