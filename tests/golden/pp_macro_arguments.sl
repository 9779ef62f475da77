// golden: compile
#define BUMP(a, f) (a) * sin((f) * u)
displacement t() {
    P += BUMP(0.1) * N;
}
