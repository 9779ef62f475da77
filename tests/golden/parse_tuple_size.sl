// golden: compile
// A parenthesised list is a triple or a matrix (16 entries); other sizes are errors.
displacement t() {
    P += (1, 2) * N;
    P += (1, 2, 3, 4) * N;
}
