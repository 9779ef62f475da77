// compiler/scene_facts.h: what the scene tells the compiler about one shader instance besides its
// parameter values and coordinate spaces (compiler/spaces.h): the options and attributes that
// option(), attribute() and depth() read (RI Spec 3.2, section 15.8, tables 15.4 and 15.5).
// affray compiles each instance with its facts, so these calls fold to constants
// (compiler/lower_surface.cpp). Without a scene (`affray compile`, `affray eval`) there are no
// facts: option() and attribute() return 0, depth() uses RenderMan's default clipping planes.
// To add a fact: fill it in the renderer (renderer/render.cpp, FactsOf) under its RI name; the
// compiler reads any name it is given.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace affray::compiler {

/// One option or attribute: a float or an array of floats, or a string.
struct FactValue {
    std::vector<double> numbers;      // a float is one number, a float[n] n of them
    std::optional<std::string> text;  // a string's value (then `numbers` is empty)
    bool operator==(const FactValue&) const = default;
};

struct SceneFacts {
    /// option() data by name: "Format" {xres, yres, pixel aspect}, "Clipping" {near, far}...
    std::map<std::string, FactValue> options;
    /// attribute() data by name: "Sides" {1 or 2}, "identifier:name"...
    std::map<std::string, FactValue> attributes;
    /// Where texture() looks for a relative file name first (Option "searchpath" "texture"),
    /// before the shader's directory and the working directory.
    std::vector<std::string> textureSearchPath;
    /// The lights a surface shader's light loops visit (illuminance; diffuse, specular and phong
    /// through it): per light slot (vm/lights.h), in order, the light's `__category` ("" if it
    /// has none). The ambient lights are not among them (ambient() sums those).
    std::vector<std::string> lightCategories;
};

/// What a compilation looked up in its Spaces and SceneFacts: the names of the spaces it mapped
/// through or checked, the options and attributes it asked for (found or not), and whether it
/// resolved a texture's file (through the texture search path). Two instances that give every one
/// of these the same value compile to the same shader, whatever else their scenes hold (a shader
/// that names no space is compiled once for a thousand objects placed apart).
struct SceneReads {
    std::set<std::string> spaces, options, attributes;
    bool textureSearchPath = false;
    /// The light slots and their categories (a surface shader's light loop).
    bool lights = false;

    bool operator==(const SceneReads&) const = default;
    void Add(const SceneReads& other) {
        spaces.insert(other.spaces.begin(), other.spaces.end());
        options.insert(other.options.begin(), other.options.end());
        attributes.insert(other.attributes.begin(), other.attributes.end());
        textureSearchPath = textureSearchPath || other.textureSearchPath;
        lights = lights || other.lights;
    }
};

/// RenderMan's default clipping planes (RI_EPSILON and RI_INFINITY as affray's scene has them),
/// which depth() uses when the facts have no "Clipping".
inline constexpr double kDefaultNearClip = 1e-10;
inline constexpr double kDefaultFarClip = 1e30;

}  // namespace affray::compiler
