// golden: compile -D=1
// -D needs a macro name: an error without a line.
displacement t() {
    P += N;
}
