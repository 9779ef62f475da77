// golden: compile
#if 1
displacement t() {
    P += N;
}
