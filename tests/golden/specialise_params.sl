// golden: eval --at 0.5,0.5 --at 0.25,0.75 --param mode=2 --param Km=1 --param octaves=3
// Parameter values from the command line choose the other branch and a longer loop.
displacement t(float Km = 0.1; float mode = 1; float octaves = 2) {
    float i, sum = 0;
    for (i = 0; i < octaves; i += 1)
        sum += pow(0.5, i) * sin(u * pow(2, i));
    if (mode == 1) P += Km * sum * N;
    else P += Km * (noise(P) + sum) * N;
}
