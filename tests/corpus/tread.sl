/*
 * tread.sl: a tyre tread of chevron blocks around the circumference (t), with a central rib and
 * sipes across the blocks. Constructs: faceforward with I, abs, mod, step, && in a condition,
 * nested ternaries.
 */
displacement tread(float Km = 0.03, chevrons = 20, sipes = 4)
{
    normal Nf = faceforward(normalize(N), I);
    float x = abs(s - 0.5);
    float phase = mod(t * chevrons + 2 * x, 1);
    float block = step(0.35, phase);
    float rib = (x < 0.06) ? 1 : 0;
    float sipe = (mod(phase * sipes, 1) < 0.1 && block > 0) ? 0.5 : 1;
    float h = x > 0.45 ? 0 : max(block * sipe, rib);
    P += Km * h * Nf;
    N = calculatenormal(P);
}
