// vm/lights.h: what a surface shader's light loops (and its trace calls) ask of the renderer. The compiler unrolls
// `illuminance` (and ambient, diffuse, specular, phong, which RI Spec 3.2 defines by it) over the
// light slots of the instance's light list; each light's L and Cl are Light instructions, which
// the interpreter answers through the LightQueries the renderer gives it for the point it shades.
// A light's colour is asked with a flag saying whether its shadow is wanted: the loop's cone test
// for that light, so that a shadow ray is traced only for lights the shader can use.
#pragma once

namespace affray::vm {

/// The component a Light instruction asks for (its operand C holds the number).
enum class LightComponent : int { Lx, Ly, Lz, ClR, ClG, ClB };
inline constexpr int kLightComponents = 6;

/// The slot of ambient(): the sum of the ambient lights' colours (its L is 0).
inline constexpr int kAmbientSlot = 255;
/// Slots 0 .. kMaxLightSlots - 1 are the lights a light loop visits, in the order of the list.
inline constexpr int kMaxLightSlots = 255;

class LightQueries {
  public:
    virtual ~LightQueries() = default;
    /// Component `component` (a LightComponent) of light `slot` at the shaded point: L, the
    /// vector from the point to the light (its length the distance; a distant light's unit
    /// direction towards it), or Cl, its colour arriving there, times what gets through to the
    /// point if `shadowed` and the light casts shadows.
    virtual double Light(int slot, int component, bool shadowed) = 0;
    /// Channel `channel` (0-2) of the colour a ray from the shaded point along `direction` sees
    /// (trace(P, R), RI Spec 3.2 section 15.5.2): the shaded colour of the surface it hits first,
    /// black where it hits nothing.
    virtual double Trace(const double direction[3], int channel) = 0;
};

}  // namespace affray::vm
