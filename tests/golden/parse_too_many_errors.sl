// golden: compile
// Past 50 errors the list stops with a count, and parsing stops.
displacement t() {
    P += @@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@@ N;
}
