// golden: eval --at 0.25,0.5
// printf changes nothing; format and concat of constants fold to a string, so they can name a
// space or be matched (match is a regular expression search): P moves by (1, 1, 0.25).
displacement t(string prefix = "wor") {
    printf("P = %p, u = %f, %s\n", P, u, prefix);
    string space = concat(prefix, "ld");
    string label = format("%s-%d-%.2f", "tile", 3, 0.5);
    float x = match("^tile-3-0\\.50$", label);
    float y = match("[0-9]", "abc") + match("l", space);
    P = transform(space, P) + point(x, y, u);
}
