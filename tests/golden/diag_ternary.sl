// golden: compile
// The two results of ?: must have compatible types.
displacement t() {
    P += u > 0.5 ? P : color(1, 0, 0);
    P += u > 0.5 ? 1 : "a";
    P = u > 0 ? matrix 1 : P;
}
