// golden: compile
// What each arithmetic operator takes.
displacement t() {
    string s = "a";
    P += "a" + 1;
    P += color(1, 0, 0) + P;
    P = P ^ 1;
    P += 1 . N;
    P = P * matrix 1;
    P += -"a";
    P += -(matrix 1);
    P = (1, "a", 2);
    matrix m = (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, "a");
    s += 1;
    m += m;
}
