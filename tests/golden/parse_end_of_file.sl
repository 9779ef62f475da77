// golden: compile
// A missing '}' is reported just after the last token, not on a line past the end.
displacement t() {
    if (u > 0.5) {
        P += N;
    }
