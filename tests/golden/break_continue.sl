// golden: eval --at 0.5,0.5
// break, continue and break 2 in nested loops: j runs 0, 1, 3 (2 is skipped, 4 breaks) for
// i = 0 and 1, then 0 for i = 2, where j == 1 leaves both loops: 7 iterations, sum 508.
displacement t() {
    float i, j, count = 0, sum = 0;
    for (i = 0; i < 5; i += 1) {
        for (j = 0; j < 5; j += 1) {
            if (j == 2) continue;
            if (j > 3) break;
            if (i == 2 && j == 1) break 2;
            count += 1;
            sum += 100 * i + j;
        }
    }
    P += (count, sum, 0);
}
