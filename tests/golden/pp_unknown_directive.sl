// golden: compile
#warn this is no directive
displacement t() {
    P += N;
}
