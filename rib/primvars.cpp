// rib/primvars.cpp: the colour primitive variables "Cs" and "Os" (RI Spec 3.2 section 4.1),
// shared by every primitive request: their declaration and count checked against the storage
// classes of the primitive (PrimvarCounts), then turned into each primitive's colour or colour
// field (scene/geometry/primvar.h) by the request's own file, which knows where its values
// lie over each piece.
#include <cmath>

#include "rib/parser.h"

namespace affray::rib {

using renderer::StorageClass;

size_t RibParser::PrimvarCounts::Of(StorageClass s) const {
    switch (s) {
        case StorageClass::Constant: return 1;
        case StorageClass::Uniform: return faces;
        case StorageClass::Varying: return varying;
        case StorageClass::Vertex: return points;
        case StorageClass::FaceVarying: return corners;
    }
    return 1;
}

void RibParser::ResolveStorage(const RibParam& p, const std::string& context, const PrimvarCounts& counts,
                               bool facevarying, RibDeclaration* d) {
    const size_t got = d->type == "string" ? p.value.strings.size() : p.value.numbers.size();
    const size_t each = d->UniformCount();
    if (!d->storage.empty() || got == counts.Of(StorageClass::Uniform) * each) return;
    std::vector<std::string> classes;
    RibDeclaration standard;
    std::string problem;
    if (const std::string text = StandardDeclaration(p.value.name);
        !text.empty() && RibDeclaration::Parse(text, &standard, &problem) && !standard.storage.empty())
        classes.push_back(standard.storage);
    for (const char* c : {"varying", "vertex", "facevarying", "constant"})
        if (facevarying || std::string(c) != "facevarying") classes.emplace_back(c);
    for (const std::string& c : classes) {
        RibDeclaration candidate = *d;
        candidate.storage = c;
        if (counts.Of(candidate.Storage()) * each != got) continue;
        Note(p.at, context + " parameter " + Quote(p.value.name) + " is declared \"" + p.value.declaration +
                       "\" without a storage class, which means uniform, but has " + std::to_string(got) +
                       (d->type == "string" ? " strings" : " numbers") + ": read as " + c);
        d->storage = c;
        return;
    }
}

bool RibParser::ColorPrimvar(const RibParam& p, const std::string& context, const PrimvarCounts& counts,
                             bool facevarying, ColorValues* out) {
    const std::string& name = p.value.name;
    const std::string declaration = p.value.declaration.empty() ? StandardDeclaration(name) : p.value.declaration;
    RibDeclaration d;
    std::string problem;
    if (!RibDeclaration::Parse(declaration, &d, &problem)) return Fail(p.at, context + " parameter: " + problem);
    if (d.type == "string" || d.UniformCount() != 3)
        return Fail(p.at, context + " parameter " + Quote(name) + " must be a color (3 numbers a value), declared " +
                              Quote(declaration));
    ResolveStorage(p, context, counts, facevarying, &d);
    StorageClass storage = d.Storage();
    if (storage == StorageClass::FaceVarying && !facevarying)  // (NuPatch)
        return Fail(p.at, context + " parameter " + Quote(name) + ": storage class " + Quote(d.storage) +
                              " is not defined on a NuPatch");
    size_t values = counts.Of(storage);
    if (p.value.strings.empty() && p.value.numbers.size() == 3 && values > 1) {
        // One colour where the class needs more ("Cs" [1 0 0] on a sphere): what was meant.
        Warn(p.at, context + " parameter " + Quote(name) + " (" + declaration + ") expects " + std::to_string(values) +
                       " colors, got one: taken as the whole primitive's");
        values = 1;
        storage = StorageClass::Constant;
    }
    if (!p.value.strings.empty() || p.value.numbers.size() != 3 * values)
        return Fail(p.at, context + " parameter " + Quote(name) + " (" + declaration + ") expects " +
                              std::to_string(values) + " color" + (values == 1 ? "" : "s") + " (" +
                              std::to_string(3 * values) + " numbers), got " +
                              (p.value.strings.empty() ? std::to_string(p.value.numbers.size()) + " numbers"
                                                       : std::string("strings")));
    out->storage = storage;
    out->values.clear();
    bool clamped = false;
    for (size_t i = 0; i < values; ++i) {
        glm::dvec3 c(p.value.numbers[3 * i], p.value.numbers[3 * i + 1], p.value.numbers[3 * i + 2]);
        if (name == "Os" && glm::clamp(c, 0.0, 1.0) != c) {
            c = glm::clamp(c, 0.0, 1.0);
            clamped = true;
        }
        out->values.push_back(c);
    }
    if (clamped) Warn(p.at, context + " parameter 'Os' components must be from 0 to 1; clamped");
    return true;
}

void RibParser::SetConstantColors(const std::optional<ColorValues> (&colors)[2], PrimitiveDesc* prim) {
    for (int k = 0; k < 2; ++k)
        if (colors[k] && colors[k]->storage == StorageClass::Constant)
            (k ? prim->opacity : prim->color) = colors[k]->values[0];
}

}  // namespace affray::rib
