// golden: compile
// The preprocessor closes a comment left open at the end of the file, with a warning (so the
// lexer's own "unterminated comment" cannot be reached from a file); the '}' it ate is missing.
displacement t() {
    P += N; /* a comment
    that never ends
}
