// golden: eval --at 0.5,0.5 --at 0.9,0.5
// Past 64 iterations a varying loop's results are NaN (null in JSON), never a wrong value.
displacement t() {
    float n = 0;
    while (n < u * 100) n += 1;
    P += n * 0.001 * N;
}
