// golden: compile
// A byte that starts no UTF-8 sequence shows as \xNN.
displacement t() {
    P += ÿN;
}
