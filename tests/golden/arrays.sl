// golden: eval --at 0.2,0.5 --at 0.7,0.5 --param w=4,5,6
// Arrays: a parameter set from the command line, a constant index and a varying one.
displacement t(float w[3] = {1, 2, 3}) {
    float a[3] = {10, 20, 30};
    float i = floor(u * 3);
    a[1] = w[2];
    P += (a[1], a[i], w[i]);
}
