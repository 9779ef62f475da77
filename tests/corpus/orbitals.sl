/*
 * orbitals.sl: concentric ridges around a jittered centre, in the style of the shader classes of
 * RenderMan Pro Server 13 and later (RSL 2): parameters read again with evalparam, members set
 * by begin() and shared with a private method, an early return, and a lighting method that a
 * displacement run leaves out.
 */
class orbitals(float Km = 0.02; float rings = 6; float wobble = 0.1; string space = "shader")
{
    uniform float m_rings = 1;
    varying point m_Pc = 0;
    varying float m_r = 0;

    public void begin()
    {
        evalparam("rings", m_rings);
        m_Pc = transform(space, P);
        m_r = distance(point(xcomp(m_Pc), ycomp(m_Pc), 0), point(0.5, 0.5, 0));
    }

    float ridge(float x)
    {
        float f = x * m_rings;
        return abs(2 * (f - floor(f)) - 1);
    }

    public void displacement(output point P; output normal N)
    {
        if (Km == 0)
            return;
        float r = m_r + wobble * (float noise(m_Pc * 4) - 0.5);
        normal Nn = normalize(N);
        P += Km * (1 - ridge(r)) * Nn;
        N = calculatenormal(P);
    }

    public void lighting(output color Ci, Oi)
    {
        color C = 0;
        illuminance(P, normalize(N), PI / 2) {
            C += Cl * (normalize(L) . normalize(N));
        }
        Ci = Cs * C;
        Oi = Os;
    }
}
