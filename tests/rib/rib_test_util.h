// tests/rib/rib_test_util.h: reading RIB text in tests, and its diagnostics as one-line strings.
#pragma once

#include <optional>
#include <string>

#include <catch2/catch.hpp>

#include "diag/diagnostic.h"
#include "rib/rib.h"
#include "scene/refine.h"

namespace affray::test {

/// A diagnostic's first line without its column, "t.rib:3: error: message" (columns, source lines
/// and carets are the golden tests' business).
inline std::string ShortDiagnostic(const diag::Diagnostic& d) {
    static const char* const kKind[] = {"error", "warning", "note"};
    return d.where.file + ":" + std::to_string(d.where.line) + ": " + kKind[static_cast<int>(d.severity)] + ": " +
           d.message;
}

/// `world` (a world block's body, its first line the file's line 2) as a whole RIB file.
inline std::string InWorld(const std::string& world) { return "WorldBegin\n" + world + "\nWorldEnd\n"; }

/// The scene of `world`, which must parse, with its meshes refined as a render prepares them
/// (RefineScene), which must succeed; its diagnostics go to *report if given.
inline renderer::SceneDesc ParseWorld(const std::string& world, diag::Report* report = nullptr) {
    diag::Report local;
    diag::Report& r = report ? *report : local;
    std::optional<renderer::SceneDesc> scene = rib::ParseRib(InWorld(world), "t.rib", &r);
    INFO(r);
    REQUIRE(scene);
    REQUIRE(renderer::RefineScene(&*scene, &r));
    return *scene;
}

/// The first error of the RIB file `text` as ShortDiagnostic gives it, from reading it or from
/// refining its meshes (RefineScene), or "" if neither fails.
inline std::string FirstError(const std::string& text) {
    diag::Report report;
    std::optional<renderer::SceneDesc> scene = rib::ParseRib(text, "t.rib", &report);
    if (scene && renderer::RefineScene(&*scene, &report)) return "";
    for (const diag::Diagnostic& d : report.all())
        if (d.severity == diag::Severity::Error) return ShortDiagnostic(d);
    return "(no error reported)";
}

/// FirstError of `world` inside a world block.
inline std::string WorldError(const std::string& world) { return FirstError(InWorld(world)); }

}  // namespace affray::test
