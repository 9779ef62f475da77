// Found by fuzz_sl: an endless loop inside other loops was unrolled to its budget once per
// iteration of the loops around it.
displacement t() {
    float i, j, k;
    for (i = 0; i < 3; i += 1)
        for (j = 0; j < 3; j += 1)
            for (k = 0; k < 1; k += 0) P += 0;
}
