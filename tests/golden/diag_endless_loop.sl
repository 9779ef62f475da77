// golden: compile
// A loop whose condition stays constant and true would unroll for ever.
displacement t() {
    float i = 0;
    while (i < 1) P += 0;
}
