// golden: compile
// A macro can put a '#' at the start of a line after preprocessing; "# 0" reads as a line
// marker with line 0.
#define HASH #
HASH 0
displacement t() {
    P += N;
}
