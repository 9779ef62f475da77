// golden: compile --stats
// Instruction counts before and after specialisation for the defaults (the same shader as
// specialise_defaults.sl), and the globals the shader reads.
displacement t(float Km = 0.1; float mode = 1; float octaves = 2) {
    float i, sum = 0;
    for (i = 0; i < octaves; i += 1)
        sum += pow(0.5, i) * sin(u * pow(2, i));
    if (mode == 1) P += Km * sum * N;
    else P += Km * noise(P) * N;
}
