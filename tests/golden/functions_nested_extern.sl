// golden: eval --at 0.25,0.5 --at 0.75,0.5
// A nested function changes its caller's variable through extern; arrays pass by reference to
// output parameters.
void fill(output float a[3]; float x) {
    a[0] = x;
    a[1] = 2 * x;
    a[2] = 3 * x;
}
displacement t() {
    float total = 0, a[3];
    void add(float x) {
        extern float total;
        total += x;
    }
    fill(a, u);
    add(a[0]);
    add(a[2]);
    P += (total, a[1], 0);
}
