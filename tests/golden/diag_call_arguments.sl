// golden: compile
// Calls to user functions: argument counts (with a note at the definition), output and array
// parameters, and types.
float f(float x) { return x; }
void dbl(float x; output float y) { y = 2 * x; }
void setf(output float y) { y = 1; }
float sum(float a[]) { return a[0]; }
float sum3(float a[3]) { return a[0] + a[1] + a[2]; }
displacement t() {
    float r = 0, b[2] = {1, 2};
    P += f(1, 2);
    dbl(1, r + 1);
    dbl(1, u);
    setf(P);
    P += f(P);
    P += sum(1);
    P += sum(r);
    P += sum3(b);
}
