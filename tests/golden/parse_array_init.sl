// golden: compile
// Lists in braces initialise arrays, and only arrays; sizes must match; locals need a size.
displacement t() {
    float x = {1, 2};
    float a[3] = {1, 2};
    float b[2] = 1;
    float c[];
    float d[2] = {1, , 2};
    P += N;
}
