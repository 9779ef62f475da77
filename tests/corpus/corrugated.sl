/*
 * corrugated.sl: corrugated iron, the simplest of the Companion's displacement examples: a sine
 * across s. Constructs: a one-line displacement with uniform parameters, sin, calculatenormal.
 */
displacement corrugated(float Km = 0.02, frequency = 16)
{
    P += Km * sin(2 * PI * frequency * s) * normalize(N);
    N = calculatenormal(P);
}
