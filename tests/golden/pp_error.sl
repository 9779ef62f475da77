// golden: compile -D WRONG
// mcpp's own messages come through with the file and line, and a caret at the line's start.
#ifdef WRONG
#error this shader needs WRONG undefined
#endif
displacement t() {
    P += N;
}
