// golden: eval --at 0.5,0.5 --param mode=down
// A string parameter compared with == and chosen from the command line; a string variable set
// in a branch.
displacement t(string mode = "up") {
    string s = "small";
    if (mode == "down") s = "large";
    float k = s == "large" ? 2 : 1;
    if (mode == "up") P += k * 0.1 * N;
    else P -= k * 0.1 * N;
}
