// golden: compile
// An endless loop whose body asks for many operations per iteration stops at the program-ops
// limit (250000), long before its 10000 iterations, within a fraction of a second: the error
// names the limit, and a note the loop being unrolled.
float f(float x) {
    return sin(x) * cos(x) + sin(2 * x) * cos(3 * x) + sin(5 * x) * cos(7 * x);
}
displacement t() {
    float i = 0, a = 0;
    while (i >= 0) {
        i += 1;
        a += f(u + i) + f(v - i) + f(u * i) + f(v * i);
    }
    P += a * N;
}
