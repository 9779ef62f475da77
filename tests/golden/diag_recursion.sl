// golden: compile
// Functions are inlined: direct and mutual recursion are errors where the cycle closes.
float f(float x) {
    return f(x - 1);
}
void g() {
    h();
}
void h() {
    g();
}
displacement t() {
    P += f(u) * N;
    g();
}
