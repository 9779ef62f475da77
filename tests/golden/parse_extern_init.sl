// golden: compile
// An extern names a caller's variable: it cannot also give it a value.
displacement t() {
    float k = 1;
    void f() {
        extern float k = 2;
        P += k * N;
    }
    f();
}
