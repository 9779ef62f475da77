// golden: compile
// What a return statement may carry.
void nothing() {
    return 1;
}
float half(float x) {
    if (x > 0) return;
    return x / 2;
}
float noreturn(float x) {
    x += 1;
}
float name() {
    if (u > 0) return "a";
    return 1;
}
displacement t() {
    nothing();
    P += (half(u) + noreturn(u) + name()) * N;
    return 1;
}
