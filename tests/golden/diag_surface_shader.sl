// golden: compile
// Only displacement shaders render.
surface t() {
    P += N;
}
