/*
 * tests/scenes/stiff/wave.sl: the stiff scenes displace with shaders/wave.sl itself, with parameter
 * overrides; the renderer looks for shaders next to the scene, so this file only includes it.
 */
#include "../../../shaders/wave.sl"
