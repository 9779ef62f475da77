// golden: compile --disasm
// The programs are compiled for the parameters' values (here the defaults): the branch on
// `mode` and the loop over `octaves` are decided, and Km becomes a constant.
displacement t(float Km = 0.1; float mode = 1; float octaves = 2) {
    float i, sum = 0;
    for (i = 0; i < octaves; i += 1)
        sum += pow(0.5, i) * sin(u * pow(2, i));
    if (mode == 1) P += Km * sum * N;
    else P += Km * noise(P) * N;
}
