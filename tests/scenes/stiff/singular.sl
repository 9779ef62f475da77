/*
 * singular.sl: functions whose argument reaches 0 inside the patch, where the bound of a region
 * around that point loses its derivative (sqrt), goes to -infinity (log) or divides by a range
 * containing 0 (sin(x) / x). The scalar value is finite everywhere except at that one point (log:
 * -infinity; sin(x)/x: 0/0).
 *
 *   Km                 amplitude
 *   kind               "sqrt": a cusp ridge sqrt(|s - centerS|) plus a cone point sqrt(r)
 *                      "log":  a funnel log(r), -infinity at the centre
 *                      "div":  a sombrero sin(k r) / (k r), 0/0 at the centre
 *   frequency          k / (2 pi) for "div"
 *   centerS, centerT   the singular point, in (s, t)
 */
displacement singular(float Km = 0.05; string kind = "sqrt"; float frequency = 6;
                      float centerS = 0.4375, centerT = 0.5625)
{
    float r = distance(point(s, t, 0), point(centerS, centerT, 0));
    float height = 0;
    if (kind == "sqrt") {
        height = sqrt(abs(s - centerS)) + sqrt(r);
    } else if (kind == "log") {
        height = log(r);
    } else {
        float x = 2 * PI * frequency * r;
        height = sin(x) / x;
    }
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}
