// golden: compile
// The preprocessor refuses control characters before the lexer sees them.
displacement t() {
    P += N;
}
