// tools/diff.cpp: `affray diff`, the image error of a render against a reference (the error
// half of the error-against-run-time report, bench/error_report.py).
#include <cmath>

#include "image/exr_writer.h"
#include "tools/commands.h"

namespace affray::tools {

int RunDiff(const DiffCommand& cmd, FILE* out, FILE* err) {
    image::ImageBuffer reference, test;
    diag::Report report;
    auto fail = [&] {
        Print(report, err);
        return diag::kExitBadInput;
    };
    if (!image::ReadExrRgba(cmd.reference, &reference, &report) || !image::ReadExrRgba(cmd.test, &test, &report))
        return fail();
    if (reference.width != test.width || reference.height != test.height) {
        report.error({cmd.test}, "the image is " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                                     " but the reference '" + cmd.reference + "' is " +
                                     std::to_string(reference.width) + "x" + std::to_string(reference.height));
        return fail();
    }
    // Over R, G and B of every pixel (alpha is 1 wherever either image has a surface).
    double sumSquares = 0, largest = 0;
    const size_t pixels = static_cast<size_t>(reference.width) * static_cast<size_t>(reference.height);
    for (size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            const double d = static_cast<double>(test.rgba[4 * p + c]) - reference.rgba[4 * p + c];
            if (std::isnan(d)) {
                const bool inTest = std::isnan(test.rgba[4 * p + c]);
                report.error({inTest ? cmd.test : cmd.reference},
                             "pixel (" + std::to_string(p % static_cast<size_t>(reference.width)) + ", " +
                                 std::to_string(p / static_cast<size_t>(reference.width)) + ") is NaN");
                return fail();
            }
            sumSquares += d * d;
            largest = std::fmax(largest, std::fabs(d));
        }
    const double rmse = pixels ? std::sqrt(sumSquares / (3.0 * static_cast<double>(pixels))) : 0.0;
    std::fprintf(out, "{\"pixels\":%zu,\"rmse\":%.17g,\"max\":%.17g}\n", pixels, rmse, largest);
    return diag::kExitSuccess;
}

}  // namespace affray::tools
