// rib/args.h: checks on the shape of a RIB request's arguments.
// Owns the rules every request shares: positional numbers given bare or as one array, a leading
// name string, token-value parameter lists with inline declarations ("uniform float Km"), and
// 4x4 matrices. It knows no request's meaning (that is rib/rib.cpp). Each check returns
// false after Fail() has recorded the message and the place of the offending token.
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

#include "rib/lexer.h"
#include "scene/scene.h"

namespace affray::rib {

using renderer::CameraDesc;
using renderer::CubicBasis;
using renderer::FilterDesc;
using renderer::LightDesc;
using renderer::ParamValue;
using renderer::PrimitiveDesc;
using renderer::Quadric;
using renderer::SceneDesc;
using renderer::ShaderRef;
using renderer::SurfaceDesc;

/// A parameter of a request with the place of its value, for messages.
struct RibParam {
    ParamValue value;
    RibPos at;
};

/// A parameter's declaration (RI 3.2 section 3: "[class] type['['n']']"), parsed.
struct RibDeclaration {
    std::string storage;  ///< constant, uniform, varying, vertex, facevarying, facevertex; "" if not given
    std::string type;     ///< float, integer, int, string, color, point, vector, normal, hpoint, matrix, ...
    int arraySize = 1;    ///< n of "type[n]"; 1 without brackets
    int components = 1;   ///< numbers (or strings) per element: 3 for color and point, 16 for matrix

    /// Parses `text`; on failure returns false with *problem saying why.
    static bool Parse(const std::string& text, RibDeclaration* out, std::string* problem);
    /// The storage class `storage` names ("" is uniform, RI's default; "facevertex" is
    /// facevarying); Parse admits no other name.
    renderer::StorageClass Storage() const;
    /// Values of a uniform (or constant) parameter: components * arraySize.
    size_t UniformCount() const { return static_cast<size_t>(components) * static_cast<size_t>(arraySize); }
};

/// The declaration RenderMan predeclares for a standard primitive variable ("vertex point" for
/// "P", "varying float[2]" for "st"...), or "" for a name it does not predeclare.
std::string StandardDeclaration(const std::string& name);

/// A name string that may carry a declaration before its last word ("uniform float Km",
/// DisplayChannel's "color Ci"): the last word, and the words before it, with the characters of
/// `blanks` (parameter names: spaces, tabs, line ends) separating and trimmed; both empty for a
/// blank string, `declaration` empty for a bare name.
struct DeclaredName {
    std::string declaration, name;
};
DeclaredName SplitDeclaredName(const std::string& text, const char* blanks = " \t\n\r");

/// Argument checks for the RIB reader, which derives from this class. Messages name the request.
class RibArgChecks {
  protected:
    /// Records the first error ("message" and its place) and returns false.
    bool Fail(RibPos at, const std::string& message);

    /// No arguments at all.
    bool NoArgs(const RibRequest& r);
    /// Exactly `count` numbers, bare or as one array (the RIB binding allows both). `names` lists
    /// them for the message ("dx dy dz").
    bool Numbers(const RibRequest& r, size_t count, const char* names, double* out);
    /// `count` leading numbers, bare or as one array, that may be followed by a parameter list;
    /// *next is set to the index of the first argument after them.
    bool LeadingNumbers(const RibRequest& r, size_t count, const char* names, double* out, size_t* next);
    /// Copies `values` to `out` if there are exactly `count` and no `bad` argument, else fails
    /// naming what was found (the shared end of Numbers and LeadingNumbers).
    bool TakeNumbers(const RibRequest& r, const std::vector<double>& values, const RibArg* bad, size_t count,
                     const char* names, double* out);
    /// A bare string as the first argument; `what` describes it ("a light shader name").
    bool LeadingString(const RibRequest& r, const char* what, std::string* out);
    /// Token-value pairs from args[first] on. The last word of a token is the name, the words
    /// before it the inline declaration; a name without one takes its Declare'd declaration, if
    /// any. A declared parameter must have values of its type (strings or numbers) and, unless
    /// its class varies over a primitive, exactly as many as the type holds. A repeated name
    /// replaces the earlier value. `checkDeclared` false skips the declarations' checks, for the
    /// parameters of a shader affray does not have, which are ignored (the RI 3.2 specification's
    /// own example gives a "uniform point" one number).
    bool ParamList(const RibRequest& r, size_t first, std::vector<RibParam>* out, bool checkDeclared = true);
    /// `p` (the value of `token`) against its declaration, as ParamList describes.
    bool CheckDeclared(const RibRequest& r, const RibArg& token, const RibParam& p);
    /// A parameter of exactly `count` numbers; `context` names the request ("'Surface \"matte\"'").
    bool ParamNumbers(const RibParam& p, const std::string& context, size_t count, double* out);
    /// A parameter of exactly 3 numbers.
    bool ParamVector(const RibParam& p, const std::string& context, glm::dvec3* out);
    /// A 4x4 affine matrix in RIB order (row-major, row vectors), returned for column vectors.
    bool Matrix(const RibRequest& r, glm::dmat4* out);

    /// 's' quoted for messages: 'Sphere'.
    static std::string Quote(const std::string& s) { return "'" + s + "'"; }
    /// A number as printed in messages (shortest of %g).
    static std::string FormatNumber(double v);

    RibPos m_errorAt;
    std::string m_errorMessage;
    /// Declare'd names and their declarations as written ("uniform float").
    std::map<std::string, std::string> m_declared;
    /// Set while a polygon mesh reads its parameter list: its uniform values are one per face,
    /// so ParamList checks only that they are whole values (the mesh checks their count).
    bool m_uniformVaries = false;
};

}  // namespace affray::rib
