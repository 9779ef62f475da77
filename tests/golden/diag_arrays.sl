// golden: compile
// Array indices, array assignment, and what can be an array.
displacement t() {
    float a[3] = {1, 2, 3};
    float x = 1;
    P += a[3] * N;
    a[-1] = 0;
    P += x[0] * N;
    P += y[0] * N;
    a = 3;
    x[0] = 3;
    P += a[P] * N;
    string s[2] = {"a", "b"};
}
