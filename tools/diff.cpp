// tools/diff.cpp: `affray diff`, the image error of a render against a reference (the error
// half of the error-against-run-time report, bench/error_report.py).
#include <cmath>

#include "renderer/image/exr_writer.h"
#include "tools/commands.h"

namespace affray::tools {

int RunDiff(const DiffCommand& cmd, FILE* out, FILE* err) {
    renderer::ImageBuffer reference, test;
    std::string error;
    if (!renderer::ReadExrRgba(cmd.reference, &reference, &error) || !renderer::ReadExrRgba(cmd.test, &test, &error)) {
        std::fprintf(err, "affray: error: %s\n", error.c_str());
        return 1;
    }
    if (reference.width != test.width || reference.height != test.height) {
        std::fprintf(err, "affray: error: '%s' is %dx%d but '%s' is %dx%d\n", cmd.reference.c_str(), reference.width,
                     reference.height, cmd.test.c_str(), test.width, test.height);
        return 1;
    }
    // Over R, G and B of every pixel (alpha is 1 wherever either image has a surface).
    double sumSquares = 0, largest = 0;
    const size_t pixels = static_cast<size_t>(reference.width) * static_cast<size_t>(reference.height);
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            const double d = static_cast<double>(test.rgba[4 * p + c]) - reference.rgba[4 * p + c];
            if (std::isnan(d)) {
                std::fprintf(err, "affray: error: pixel %zu of one image is NaN\n", p);
                return 1;
            }
            sumSquares += d * d;
            largest = std::fmax(largest, std::fabs(d));
        }
    const double rmse = pixels ? std::sqrt(sumSquares / (3.0 * static_cast<double>(pixels))) : 0.0;
    std::fprintf(out, "{\"pixels\":%zu,\"rmse\":%.17g,\"max\":%.17g}\n", pixels, rmse, largest);
    return 0;
}

}  // namespace affray::tools
