// golden: compile
// An array size is a positive integer (up to a million).
displacement t() {
    float a[0];
    float b[2.5];
    float c[2000000];
    P += N;
}
