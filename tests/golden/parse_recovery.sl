// golden: compile
// A bad statement is skipped up to its ';' and the next statement is checked again. After an
// error three tokens must be read before the next is reported, so `float = 1;` right after the
// first mistake goes unsaid.
displacement t() {
    P += * N;
    float = 1;
    P += N;
    if u > 0 P += N;
    P += (N;
}
