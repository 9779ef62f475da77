// golden: compile
// Characters no token starts with, shown as themselves (UTF-8 sequences too); the parser does
// not add a syntax error where the lexer already complained.
displacement t() {
    P += N @ 2;
    P += $N;
    P += `N`;
    float été = 1;
}
