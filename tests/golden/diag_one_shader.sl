// golden: compile
displacement a() {
    P += N;
}
displacement b() {
    P += 2 * N;
}
