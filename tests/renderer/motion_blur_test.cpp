// tests/renderer/motion_blur_test.cpp: motion blur (Shutter, motion blocks of transforms) against a
// brute force built from still renders alone: the image of a moving scene is the mean over the
// shutter's times of still images of the scene where it stands at each time. Both estimate the
// same integral over pixel and time; the scene has a displaced sphere that slides or spins, its
// shadow on a floor, and a camera that moves.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>

#include "tests/renderer/render_text.h"

using namespace affray;
using namespace affray::renderer;

namespace {
constexpr int kWidth = 16, kHeight = 12;
/// Samples per pixel, x and y, of the blurred render and of each still: the stills then sample the
/// very positions the blurred render does, so the comparison measures the sampling of time alone
/// (stills of 4 x 4 samples would differ from the blurred render by their coarser sampling of
/// the pixel: 0.018 RMSE between two still renders).
constexpr int kSamples = 16;
/// The times of the brute force: stratum centres of the shutter.
constexpr int kTimes = 16;

/// A displaced sphere placed by `sphere` (transform requests, perhaps a motion block) over a
/// lit floor it shadows, seen from a camera placed by `camera`; `light` adds its requests after
/// the scene's two lights.
std::string Scene(const std::string& camera, const std::string& sphere, int samples, const std::string& options = "",
                  const std::string& light = "") {
    std::ostringstream rib;
    rib.precision(17);
    rib << "Format " << kWidth << ' ' << kHeight << " 1\nPixelSamples " << samples << ' ' << samples
        << "\nPixelFilter \"box\" 1 1\nProjection \"perspective\" \"fov\" [40]\n"
        << options << camera << "Translate 0 0 4\nRotate -120 1 0 0\nWorldBegin\n"
        << "Attribute \"light\" \"shadows\" \"on\"\n"
        << "LightSource \"ambientlight\" 1 \"intensity\" [0.2]\n"
        << "LightSource \"distantlight\" 2 \"intensity\" [0.7] \"from\" [1 1 2] \"to\" [0 0 0]\n"
        << light << "Surface \"matte\"\n"
        << "Patch \"bilinear\" \"P\" [-3 -3 -0.6  3 -3 -0.6  -3 3 -0.6  3 3 -0.6]\n"
        << "AttributeBegin\n"
        << sphere << "Color [0.9 0.5 0.2]\nDisplacement \"bumps\" \"Km\" [0.08] \"frequency\" [4]\n"
        << "Sphere 0.5 -0.5 0.5 360\nAttributeEnd\nWorldEnd\n";
    return rib.str();
}

/// The mean of still renders at kTimes times (stratum centres of [0, 1)), each made by
/// `still`(time) -> RIB.
template <typename Still>
image::ImageBuffer MeanOfStills(Still still) {
    image::ImageBuffer mean;
    std::vector<double> sum;
    for (int i = 0; i < kTimes; ++i) {
        const image::ImageBuffer view = test::RenderText(still((i + 0.5) / kTimes));
        if (sum.empty()) {
            sum.assign(view.rgba.size(), 0.0);
            mean = view;
        }
        for (size_t k = 0; k < sum.size(); ++k) sum[k] += view.rgba[k];
    }
    for (size_t k = 0; k < sum.size(); ++k) mean.rgba[k] = float(sum[k] / kTimes);
    return mean;
}

std::string Translate(double x, double y, double z) {
    std::ostringstream out;
    out.precision(17);
    out << "Translate " << x << ' ' << y << ' ' << z << "\n";
    return out.str();
}

/// Checks a blurred render against the brute force and against the still image at time 0.
void CheckBlur(const image::ImageBuffer& blurred, const image::ImageBuffer& mean, const image::ImageBuffer& still,
               double bound, double ratio) {
    const double error = test::RgbRmse(blurred, mean), blur = test::RgbRmse(still, mean);
    INFO("RMSE of the blurred image against the brute force " << error << ", of the still image " << blur);
    CHECK(error < bound);
    // The blur is there to be measured: the still image differs several times more.
    CHECK(blur > ratio * error);
}

}  // namespace

TEST_CASE("motion blur: a sliding displaced sphere is the mean of still spheres over the shutter",
          "[renderer][motion]") {
    const std::string motion = "MotionBegin [0 1]\n" + Translate(-0.7, 0, 0) + Translate(0.7, 0.2, 0) + "MotionEnd\n";
    const image::ImageBuffer blurred = test::RenderText(Scene("", motion, kSamples, "Shutter 0 1\n"));
    const image::ImageBuffer mean =
        MeanOfStills([](double t) { return Scene("", Translate(-0.7 + 1.4 * t, 0.2 * t, 0), kSamples); });
    const image::ImageBuffer still = test::RenderText(Scene("", Translate(-0.7, 0, 0), kSamples));
    // Measured: 0.0046, against 0.138 for the still image. Planted faults: shadow rays at time 0
    // give 0.077; hit points, normals and tangents left where the geometry is placed, 0.016.
    CheckBlur(blurred, mean, still, 0.008, 10);
}

TEST_CASE("motion blur: a light under a moving transform moves, its shadows with it", "[renderer][motion]") {
    // A point light sliding across above the still sphere: its light and the sphere's shadow
    // sweep the floor.
    auto light = [](const std::string& placed) {
        return "AttributeBegin\n" + placed + "LightSource \"pointlight\" 3 \"intensity\" [3] \"from\" [0 0 1.5]\n" +
               "AttributeEnd\nIlluminate 3 1\n";
    };
    const std::string motion = "MotionBegin [0 1]\n" + Translate(-1.2, 0, 0) + Translate(1.2, 0, 0) + "MotionEnd\n";
    const image::ImageBuffer blurred = test::RenderText(Scene("", "", kSamples, "Shutter 0 1\n", light(motion)));
    const image::ImageBuffer mean =
        MeanOfStills([&](double t) { return Scene("", "", kSamples, "", light(Translate(-1.2 + 2.4 * t, 0, 0))); });
    const image::ImageBuffer still = test::RenderText(Scene("", "", kSamples, "", light(Translate(-1.2, 0, 0))));
    // Measured: 0.0032, against 0.153 for the still image; the light left at time 0 (a planted
    // fault) gives 0.153.
    CheckBlur(blurred, mean, still, 0.008, 5);
}

TEST_CASE("motion blur: a spinning sphere and a moving camera", "[renderer][motion]") {
    SECTION("a rotation sampled at three times is piecewise linear between them") {
        // Between its samples the matrix is interpolated, not the angle: the brute force
        // interpolates the same matrices (a ConcatTransform of each time's).
        const std::string motion =
            "MotionBegin [0 0.5 1]\nRotate 0 0 0 1\nRotate 45 0 0 1\nRotate 90 0 0 1\nMotionEnd\n";
        const image::ImageBuffer blurred = test::RenderText(Scene("", motion, kSamples, "Shutter 0 1\n"));
        auto matrix = [](double t) {
            const double a0 = t < 0.5 ? 0 : 45, a1 = t < 0.5 ? 45 : 90, w = t < 0.5 ? 2 * t : 2 * t - 1;
            const double c = (1 - w) * std::cos(a0 * M_PI / 180) + w * std::cos(a1 * M_PI / 180);
            const double s = (1 - w) * std::sin(a0 * M_PI / 180) + w * std::sin(a1 * M_PI / 180);
            std::ostringstream out;
            out.precision(17);
            out << "ConcatTransform [" << c << ' ' << s << " 0 0  " << -s << ' ' << c << " 0 0  0 0 1 0  0 0 0 1]\n";
            return out.str();
        };
        const image::ImageBuffer mean = MeanOfStills([&](double t) { return Scene("", matrix(t), kSamples); });
        const image::ImageBuffer still = test::RenderText(Scene("", "", kSamples));
        // Measured: 0.0039, against 0.016 for the still image (the bumps move, the outline does
        // not); shadow rays at time 0 give 0.0095.
        CheckBlur(blurred, mean, still, 0.008, 3);
    }
    SECTION("a camera moving across the scene") {
        const std::string motion = "MotionBegin [0 1]\n" + Translate(0.5, 0, 0) + Translate(-0.5, 0, 0) + "MotionEnd\n";
        const image::ImageBuffer blurred = test::RenderText(Scene(motion, "", kSamples, "Shutter 0 1\n"));
        const image::ImageBuffer mean =
            MeanOfStills([](double t) { return Scene(Translate(0.5 - t, 0, 0), "", kSamples); });
        const image::ImageBuffer still = test::RenderText(Scene(Translate(0.5, 0, 0), "", kSamples));
        // Measured: 0.0045, against 0.135 for the still image.
        CheckBlur(blurred, mean, still, 0.008, 10);
    }
}

TEST_CASE("motion blur: a shutter that does not open, or a scene that does not move, renders the still image",
          "[renderer][motion]") {
    const std::string motion = "MotionBegin [0 1]\n" + Translate(-0.7, 0, 0) + Translate(0.7, 0, 0) + "MotionEnd\n";
    // Shutter 0 0 (the default): every sample at time 0, where the block's first sample places it.
    CHECK(test::RgbRmse(test::RenderText(Scene("", motion, 2)),
                        test::RenderText(Scene("", Translate(-0.7, 0, 0), 2))) == 0);
    // Shutter 0.5 0.5: halfway.
    CHECK(test::RgbRmse(test::RenderText(Scene("", motion, 2, "Shutter 0.5 0.5\n")),
                        test::RenderText(Scene("", Translate(0, 0, 0), 2))) < 1e-5);
    // An open shutter over a scene that stands still: the same image, bit for bit.
    CHECK(test::RgbRmse(test::RenderText(Scene("", Translate(0.2, 0, 0), 2, "Shutter 0 1\n")),
                        test::RenderText(Scene("", Translate(0.2, 0, 0), 2))) == 0);
}

TEST_CASE("motion blur: displacement shaders see time and dtime, the shutter's opening and length",
          "[renderer][motion]") {
    // A displacement is evaluated once for all the shutter's times, at its opening (as a Reyes
    // renderer shades): the shader reading time and dtime renders as one given their values.
    test::TempDir dir;
    dir.Write("timed.sl",
              "displacement timed(float Km = 0.1) {\n"
              "    P += normalize(N) * Km * (time + 2 * dtime);\n"
              "    N = calculatenormal(P);\n"
              "}\n");
    dir.Write("fixed.sl",
              "displacement fixed(float Km = 0.1; float at = 0) {\n"
              "    P += normalize(N) * Km * at;\n"
              "    N = calculatenormal(P);\n"
              "}\n");
    auto scene = [&](const std::string& shutter, const std::string& displacement) {
        return "Format 16 12 1\nPixelSamples 2 2\nProjection \"perspective\" \"fov\" [40]\n" + shutter +
               "Option \"searchpath\" \"shader\" [\"" + dir.Path("") + ":&\"]\nTranslate 0 0 3\nWorldBegin\n" +
               "LightSource \"distantlight\" 1 \"from\" [1 1 -2] \"to\" [0 0 0]\nSurface \"matte\"\n" + displacement +
               "\nSphere 0.5 -0.5 0.5 360\nWorldEnd\n";
    };
    const image::ImageBuffer timed = test::RenderText(scene("Shutter 0.25 0.75\n", "Displacement \"timed\""));
    CHECK(test::RgbRmse(timed,
                        test::RenderText(scene("Shutter 0.25 0.75\n", "Displacement \"fixed\" \"at\" [1.25]"))) == 0);
    // The default shutter (0 0): both are 0.
    CHECK(test::RgbRmse(test::RenderText(scene("", "Displacement \"timed\"")),
                        test::RenderText(scene("", "Displacement \"fixed\""))) == 0);
    // The displacement is there to be seen.
    CHECK(test::RgbRmse(timed, test::RenderText(scene("Shutter 0.25 0.75\n", "Displacement \"fixed\""))) > 0.01);
}
