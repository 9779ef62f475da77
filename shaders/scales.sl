/*
 * scales.sl: overlapping round scales in offset rows, written as a shader class (RenderMan Shading
 * Language 2). A displacement run declares the members, calls begin(), then the displacement
 * method; the surface method is not part of it. Exercises classes and methods, members shared
 * between methods, evalparam, 2-D cellnoise, mod and smoothstep.
 *
 *   Km          height of a scale
 *   frequency   scales per unit of shader space
 *   jitter      how far each scale moves sideways in its row, as a fraction of its width
 */
class scales(float Km = 0.03, frequency = 12, jitter = 0.3)
{
    varying point m_Pshad = 0;
    uniform float m_frequency = 1;

    public void begin()
    {
        evalparam("frequency", m_frequency);
        m_Pshad = transform("shader", P) * m_frequency;
    }

    // One scale over its cell, (x, y) from its centre: a dome that rises towards its lower edge,
    // where it overlaps the row below.
    float dome(float x, y)
    {
        float r = sqrt(x * x + (y - 0.5) * (y - 0.5));
        return smoothstep(0.75, 0.1, r) * (1.2 - y);
    }

    public void displacement(output point P; output normal N)
    {
        float ss = xcomp(m_Pshad), tt = ycomp(m_Pshad);
        float row = floor(tt);
        ss += 0.5 * mod(row, 2);
        float col = floor(ss);
        float shift = jitter * (float cellnoise(col, row) - 0.5);
        P += Km * dome(ss - col - 0.5 - shift, tt - row) * normalize(N);
        N = calculatenormal(P);
    }

    public void surface(output color Ci, Oi)
    {
        normal Nf = faceforward(normalize(N), I);
        Oi = Os;
        Ci = Os * Cs * (ambient() + diffuse(Nf));
    }
}
