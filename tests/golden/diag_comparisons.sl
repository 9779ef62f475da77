// golden: compile
// What each comparison and logical operator takes.
void nothing() { }
displacement t() {
    matrix m = 1;
    if (P < point(1, 1, 1)) P += N;
    if (P == color(1, 1, 1)) P += N;
    if ("a" < "b") P += N;
    if ("a" == 1) P += N;
    if (P && 1) P += N;
    if (m == P) P += N;
    if (nothing() == 1) P += N;
}
