// golden: compile
// \n \t \\ and \" are the escapes; any other is an error at the backslash.
displacement t(string mode = "a\tb\qc") {
    if (mode == "x") P += N;
}
