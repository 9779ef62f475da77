// golden: compile
// Shader classes (RSL 2): one without a displacement method, and the errors of its methods.
class notdisplacing(float Kd = 1)
{
    void begin(float x) { }
    void surface(output color Ci, Oi) { Ci = Kd; }
    void surface(output color Ci, Oi) { Ci = 1; }
}

class wrongparams()
{
    public void displacement(output point Pd) { }
}
