/*
 * tests/scenes/stiff/lumpy.sl: lumps of 3D noise of the surface point along the normal. The noise is of
 * P, not of (s, t), so the displaced sphere stays closed at its poles, where every s meets; there
 * the tangent dPdu vanishes and the normal must come from elsewhere (renderer/quadric.h).
 *
 *   Km         amplitude (the height runs over Km * [-0.5, 0.5])
 *   frequency  lumps per unit length
 */
displacement lumpy(float Km = 0.2; float frequency = 3)
{
    P += Km * (noise(P * frequency) - 0.5) * normalize(N);
    N = calculatenormal(P);
}
