// golden: compile
// A string runs to the end of its line at most; the preprocessor finds it first (so the
// lexer's own "unterminated string" cannot be reached from a file).
displacement t(string mode = "up) {
    P += N;
}
