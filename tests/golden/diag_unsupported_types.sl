// golden: compile
// void is a return type only.
displacement t() {
    void nothing;
    P += N;
}
