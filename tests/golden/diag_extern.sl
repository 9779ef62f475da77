// golden: compile
// An extern names a variable of an enclosing scope, with its type.
void f() {
    extern float nowhere;
}
displacement t() {
    float k = 1;
    extern float q;
    void g() { extern point k; }
    f();
    g();
    P += k * N;
}
