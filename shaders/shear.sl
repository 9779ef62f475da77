/*
 * shear.sl: a displacement along the surface, not across it: P moves along the tangents dPdu
 * and dPdv by waves of the other parameter, and bulges along N by |sin|, so the result is not a
 * height field and has creases.
 *
 *   Km         tangential amplitude
 *   bulge      normal amplitude of the creased ridges
 *   frequency  waves per unit of s and t
 */
displacement shear(float Km = 0.03, bulge = 0.05, frequency = 3)
{
    float k = 2 * PI * frequency;
    vector along = Km * (sin(k * t) * normalize(dPdu) + cos(k * s) * normalize(dPdv));
    P += along + bulge * abs(sin(k * (s + t))) * normalize(N);
    N = calculatenormal(P);
}
