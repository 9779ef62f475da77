// tests/scene/geometry/camera_test.cpp: camera rays (scene/geometry/camera.*) against the RenderMan screen
// window worked out by hand, for wide and tall images, fov, orthographic and a moved camera.
#include "scene/geometry/camera.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "rib/rib.h"

#include "tests/test_util.h"

using namespace affray::renderer;
using affray::rib::ParseRib;

namespace {

using affray::test::RequireVec;

CameraDesc Desc(int xres, int yres, double fov = 90, bool perspective = true, double pixelAspect = 1) {
    CameraDesc d;
    d.xres = xres;
    d.yres = yres;
    d.fovDegrees = fov;
    d.perspective = perspective;
    d.pixelAspect = pixelAspect;
    return d;
}

}  // namespace

TEST_CASE("The center ray runs along camera +z", "[renderer][camera]") {
    Camera camera(Desc(101, 77, 40));
    Ray ray = camera.GenerateRay(101 / 2.0, 77 / 2.0);
    RequireVec(ray.origin, {0, 0, 0});
    RequireVec(ray.dir, {0, 0, 1});
    RequireVec(camera.Position(), {0, 0, 0});
}

TEST_CASE("Corner rays hit the screen window corners", "[renderer][camera]") {
    SECTION("square image, fov 90: screen [-1,1]^2 on z = 1") {
        Camera camera(Desc(100, 100));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-1, 1, 1)));  // top-left
        RequireVec(camera.GenerateRay(100, 100).dir, glm::normalize(glm::dvec3(1, -1, 1)));
        RequireVec(camera.GenerateRay(100, 0).dir, glm::normalize(glm::dvec3(1, 1, 1)));
        // Pixel centers at +0.5: pixel (0,0) is half a pixel in from the corner.
        RequireVec(camera.GenerateRay(0.5, 0.5).dir, glm::normalize(glm::dvec3(-0.99, 0.99, 1)));
    }
    SECTION("wide image (a = 2): screen [-2,2] x [-1,1]") {
        Camera camera(Desc(200, 100));
        CHECK(camera.ScreenWindow() == glm::dvec4(-2, 2, -1, 1));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-2, 1, 1)));
        RequireVec(camera.GenerateRay(200, 100).dir, glm::normalize(glm::dvec3(2, -1, 1)));
    }
    SECTION("tall image (a = 1/2): screen [-1,1] x [-2,2]") {
        Camera camera(Desc(100, 200));
        CHECK(camera.ScreenWindow() == glm::dvec4(-1, 1, -2, 2));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-1, 2, 1)));
        RequireVec(camera.GenerateRay(100, 200).dir, glm::normalize(glm::dvec3(1, -2, 1)));
    }
    SECTION("non-square pixels widen the frame") {
        Camera camera(Desc(100, 100, 90, true, 2.0));
        CHECK(camera.ScreenWindow() == glm::dvec4(-2, 2, -1, 1));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-2, 1, 1)));
    }
}

TEST_CASE("The field of view spans the shorter image axis", "[renderer][camera]") {
    double t = std::tan(glm::radians(30.0));  // fov 60
    Camera wide(Desc(300, 100, 60));
    // Top edge, center column: exactly half the fov above the axis.
    Ray top = wide.GenerateRay(150, 0);
    CHECK(std::atan2(top.dir.y, top.dir.z) == Approx(glm::radians(30.0)));
    RequireVec(wide.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-3 * t, t, 1)));

    Camera tall(Desc(100, 300, 60));
    Ray right = tall.GenerateRay(100, 150);
    CHECK(std::atan2(right.dir.x, right.dir.z) == Approx(glm::radians(30.0)));
}

TEST_CASE("Orthographic rays are parallel, from the screen window", "[renderer][camera]") {
    Camera camera(Desc(200, 100, 90, false));
    Ray corner = camera.GenerateRay(0, 0);
    RequireVec(corner.origin, {-2, 1, 0});
    RequireVec(corner.dir, {0, 0, 1});
    Ray center = camera.GenerateRay(100, 50);
    RequireVec(center.origin, {0, 0, 0});
    RequireVec(center.dir, {0, 0, 1});
    CHECK(camera.PixelAngle() == 0);
    CHECK(camera.PixelWidth() == Approx(0.02));
    CHECK(camera.Footprint(1000) == Approx(0.02));
}

TEST_CASE("Rays come out in world space", "[renderer][camera]") {
    // The world origin 5 units ahead of a camera turned 90 degrees about y.
    CameraDesc desc = Desc(64, 64);
    desc.worldToCamera =
        glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 5)), glm::radians(90.0), glm::dvec3(0, 1, 0));
    Camera camera(desc);
    glm::dvec3 eye = camera.Position();
    RequireVec(glm::dvec3(desc.worldToCamera * glm::dvec4(eye, 1)), {0, 0, 0});
    Ray ray = camera.GenerateRay(32, 32);
    RequireVec(ray.origin, eye);
    // The center ray reaches the world origin after 5 units.
    RequireVec(ray.origin + 5.0 * ray.dir, {0, 0, 0});
    CHECK(glm::length(ray.dir) == Approx(1));

    // A scaled world->camera transform still gives unit directions.
    desc.worldToCamera = glm::scale(glm::dmat4(1.0), glm::dvec3(2, 2, 2));
    Ray scaled = Camera(desc).GenerateRay(0, 0);
    CHECK(glm::length(scaled.dir) == Approx(1));
    RequireVec(scaled.dir, glm::normalize(glm::dvec3(-1, 1, 1)));
}

TEST_CASE("A RIB camera places the eye where the RIB says", "[renderer][camera]") {
    affray::diag::Report error;
    auto scene = ParseRib(
        "Format 64 48 1\nProjection \"perspective\" \"fov\" 45\nTranslate 0 0 5\n"
        "WorldBegin\nWorldEnd\n",
        "t.rib", &error);
    REQUIRE(scene);
    Camera camera(scene->camera);
    RequireVec(camera.Position(), {0, 0, -5});
    RequireVec(camera.GenerateRay(32, 24).dir, {0, 0, 1});
}

TEST_CASE("PixelAngle is the angle of one pixel at the image center", "[renderer][camera]") {
    Camera camera(Desc(100, 100));
    // The center pixel spans screen [-0.01, 0.01] on the plane z = 1.
    CHECK(camera.PixelAngle() == Approx(2 * std::atan(0.01)));
    CHECK(camera.PixelWidth() == 0);
    CHECK(camera.Footprint(10) == Approx(10 * camera.PixelAngle()));
    Camera narrow(Desc(100, 100, 10));
    CHECK(narrow.PixelAngle() == Approx(2 * std::atan(0.01 * std::tan(glm::radians(5.0)))));
}

TEST_CASE("ScreenWindow maps its edges to the image edges", "[renderer][camera]") {
    SECTION("an off-center window, perspective fov 90") {
        CameraDesc desc = Desc(100, 100);
        desc.screenWindow = glm::dvec4(0, 1, 0, 1);  // the upper-right quarter of the default
        Camera camera(desc);
        CHECK(camera.ScreenWindow() == glm::dvec4(0, 1, 0, 1));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(0, 1, 1)));
        RequireVec(camera.GenerateRay(100, 100).dir, glm::normalize(glm::dvec3(1, 0, 1)));
        RequireVec(camera.GenerateRay(50, 50).dir, glm::normalize(glm::dvec3(0.5, 0.5, 1)));
    }
    SECTION("a window whose shape differs from the image stretches it") {
        CameraDesc desc = Desc(200, 100, 60);
        desc.screenWindow = glm::dvec4(-1, 1, -1, 1);
        double t = std::tan(glm::radians(30.0));
        RequireVec(Camera(desc).GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-t, t, 1)));
    }
    SECTION("it wins over FrameAspectRatio") {
        CameraDesc desc = Desc(100, 100);
        desc.frameAspectRatio = 2;
        desc.screenWindow = glm::dvec4(-0.5, 0.5, -0.25, 0.25);
        Camera camera(desc);
        CHECK(camera.ScreenWindow() == glm::dvec4(-0.5, 0.5, -0.25, 0.25));
        RequireVec(camera.GenerateRay(100, 0).dir, glm::normalize(glm::dvec3(0.5, 0.25, 1)));
    }
    SECTION("a reversed window mirrors the image") {
        CameraDesc desc = Desc(100, 100);
        desc.screenWindow = glm::dvec4(1, -1, -1, 1);
        RequireVec(Camera(desc).GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(1, 1, 1)));
    }
    SECTION("orthographic ray origins span the window") {
        CameraDesc desc = Desc(100, 50, 90, false);
        desc.screenWindow = glm::dvec4(-10, 10, 0, 10);
        Camera camera(desc);
        RequireVec(camera.GenerateRay(0, 0).origin, {-10, 10, 0});
        RequireVec(camera.GenerateRay(100, 50).origin, {10, 0, 0});
        CHECK(camera.PixelWidth() == Approx(0.2));  // 20 / 100 across, 10 / 50 down
    }
    SECTION("the pixel angle follows the window") {
        CameraDesc desc = Desc(100, 100);
        desc.screenWindow = glm::dvec4(-0.5, 0.5, -0.5, 0.5);
        CHECK(Camera(desc).PixelAngle() == Approx(2 * std::atan(0.005)));
    }
}

TEST_CASE("FrameAspectRatio sets the default screen window", "[renderer][camera]") {
    SECTION("wide frame on a square image: [-2,2] x [-1,1]") {
        CameraDesc desc = Desc(100, 100);
        desc.frameAspectRatio = 2;
        Camera camera(desc);
        CHECK(camera.ScreenWindow() == glm::dvec4(-2, 2, -1, 1));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-2, 1, 1)));
    }
    SECTION("tall frame on a wide image: [-1,1] x [-2,2]") {
        CameraDesc desc = Desc(200, 100);
        desc.frameAspectRatio = 0.5;
        Camera camera(desc);
        CHECK(camera.ScreenWindow() == glm::dvec4(-1, 1, -2, 2));
        RequireVec(camera.GenerateRay(200, 100).dir, glm::normalize(glm::dvec3(1, -2, 1)));
    }
    SECTION("it overrides the pixel aspect ratio") {
        CameraDesc desc = Desc(100, 100, 90, true, 2.0);
        desc.frameAspectRatio = 1;
        CHECK(Camera(desc).ScreenWindow() == glm::dvec4(-1, 1, -1, 1));
    }
    SECTION("from RIB") {
        affray::diag::Report error;
        auto scene = ParseRib(
            "Format 200 100 1\nFrameAspectRatio 1\nProjection "
            "\"perspective\"\nWorldBegin\nWorldEnd\n",
            "t.rib", &error);
        REQUIRE(scene);
        Camera camera(scene->camera);
        CHECK(camera.ScreenWindow() == glm::dvec4(-1, 1, -1, 1));
        RequireVec(camera.GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(-1, 1, 1)));

        scene = ParseRib(
            "Format 200 100 1\nScreenWindow [0 2 -1 0]\nProjection \"perspective\"\n"
            "WorldBegin\nWorldEnd\n",
            "t.rib", &error);
        REQUIRE(scene);
        RequireVec(Camera(scene->camera).GenerateRay(0, 0).dir, glm::normalize(glm::dvec3(0, 0, 1)));
        RequireVec(Camera(scene->camera).GenerateRay(200, 100).dir, glm::normalize(glm::dvec3(2, -1, 1)));
    }
}

TEST_CASE("ToRaster inverts the ray through a raster position, at any depth", "[renderer][camera]") {
    for (bool perspective : {true, false}) {
        CameraDesc d = Desc(320, 200, 50, perspective, 1.5);
        d.worldToCamera = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(1, -2, 7)), 0.3, glm::dvec3(1, 1, 0));
        const Camera camera(d);
        for (double x : {0.0, 17.25, 160.0, 319.5})
            for (double y : {0.0, 99.5, 200.0})
                for (double t : {0.5, 3.0, 40.0}) {
                    const Ray ray = camera.GenerateRay(x, y);
                    const glm::dvec3 p = glm::dvec3(d.worldToCamera * glm::dvec4(ray.origin + t * ray.dir, 1.0));
                    glm::dvec2 raster;
                    REQUIRE(camera.ToRaster(p, &raster));
                    CHECK(raster.x == Approx(x).margin(1e-9));
                    CHECK(raster.y == Approx(y).margin(1e-9));
                }
        // Behind a perspective camera's eye there is no raster position.
        glm::dvec2 raster;
        CHECK(camera.ToRaster(glm::dvec3(0.1, 0.2, -1), &raster) == !perspective);
        CHECK(camera.ToRaster(glm::dvec3(0.1, 0.2, 0), &raster) == !perspective);
    }
}

TEST_CASE("A lens ray starts on the lens and passes where the pinhole ray meets the focal plane",
          "[renderer][camera]") {
    affray::diag::Report error;
    auto scene = ParseRib(
        "Format 64 48 1\nProjection \"perspective\" \"fov\" 40\nDepthOfField 2.8 0.5 7\nRotate 20 0 1 0\n"
        "Translate 1 -2 5\nWorldBegin\nWorldEnd\n",
        "t.rib", &error);
    INFO(error);
    REQUIRE(scene);
    REQUIRE(scene->camera.fstop == 2.8);
    const Camera camera(scene->camera);
    REQUIRE(camera.HasLens());
    CHECK(camera.LensRadius() == Approx(0.5 * 0.5 / 2.8));
    const glm::dmat4& toCamera = scene->camera.worldToCamera;
    for (const glm::dvec2 raster : {glm::dvec2(0, 0), glm::dvec2(32, 24), glm::dvec2(63.5, 10.25)}) {
        const Ray pinhole = camera.GenerateRay(raster.x, raster.y);
        const glm::dvec3 pc(toCamera * glm::dvec4(pinhole.dir, 0.0));
        const glm::dvec3 focus = pinhole.origin + pinhole.dir * (7.0 / pc.z);  // on camera z = 7
        for (const glm::dvec2 lens : {glm::dvec2(0, 0), glm::dvec2(1, 1), glm::dvec2(0.3, 0.9), glm::dvec2(0.5)}) {
            INFO("raster " << raster.x << "," << raster.y << " lens " << lens.x << "," << lens.y);
            const Ray r = camera.GenerateRay(raster.x, raster.y, lens);
            const glm::dvec3 origin(toCamera * glm::dvec4(r.origin, 1.0));
            CHECK(origin.z == Approx(0).margin(1e-12));
            CHECK(std::hypot(origin.x, origin.y) <= camera.LensRadius() * (1 + 1e-12));
            CHECK(glm::length(r.dir) == Approx(1));
            // The ray reaches the focus point: its distance from the line is rounding.
            const glm::dvec3 toFocus = focus - r.origin;
            CHECK(glm::length(toFocus - glm::dot(toFocus, r.dir) * r.dir) < 1e-12 * glm::length(toFocus));
        }
        // The lens's centre gives the pinhole ray.
        const Ray centre = camera.GenerateRay(raster.x, raster.y, glm::dvec2(0.5));
        RequireVec(centre.origin, pinhole.origin);
        RequireVec(centre.dir, pinhole.dir);
    }
    // No lens without DepthOfField, with an infinite fstop, or with no arguments.
    for (const char* dof : {"", "DepthOfField 1e38 1 1\n", "DepthOfField\n", "DepthOfField 2 1 3\nDepthOfField\n"}) {
        auto s =
            ParseRib(std::string("Projection \"perspective\"\n") + dof + "WorldBegin\nWorldEnd\n", "t.rib", &error);
        REQUIRE(s);
        CHECK_FALSE(Camera(s->camera).HasLens());
    }
    // A lens too small to move any image by a hundredth of a pixel between the clipping planes is
    // the pinhole it draws; the same lens with the near plane at 1e-4 (images there move by
    // radius / 1e-4 = 5e-3 on the plane z = 1, more than a pixel) is a lens. A pixel there is
    // 2 tan(45 deg) / 480 = 4.2e-3 at the default 640x480 and fov 90.
    auto lens = [&](const std::string& rib) {
        auto s = ParseRib("Projection \"perspective\"\n" + rib + "WorldBegin\nWorldEnd\n", "t.rib", &error);
        REQUIRE(s);
        return Camera(s->camera).HasLens();
    };
    CHECK_FALSE(lens("Clipping 0.1 10000\nDepthOfField 1000000 1 1\n"));  // radius 5e-7: moves images by 5e-6
    CHECK(lens("Clipping 0.0001 10000\nDepthOfField 1000000 1 1\n"));
    CHECK(lens("DepthOfField 1000000 1 1\n"));                    // the RI default near plane, 1e-10
    CHECK(lens("Clipping 0.1 10000\nDepthOfField 22 0.05 1\n"));  // a real lens: radius 1.1e-3
}

TEST_CASE("The lens map takes the unit square onto the disc, area for area", "[renderer][camera]") {
    CHECK(Camera::LensPoint({0.5, 0.5}) == glm::dvec2(0, 0));
    // The square's edges go to the circle.
    for (double t = 0; t <= 1; t += 0.125)
        for (const glm::dvec2 u : {glm::dvec2(t, 0), glm::dvec2(t, 1), glm::dvec2(0, t), glm::dvec2(1, t)})
            CHECK(glm::length(Camera::LensPoint(u)) == Approx(1).margin(1e-12));
    // Equal areas: each of 8 x 8 cells, sampled finely, covers 1/64 of the disc; the rings
    // |p| <= r hold the fraction r^2 of the points (uniform over the disc).
    constexpr int kCells = 8, kFine = 32;
    int inside[4] = {0, 0, 0, 0};
    const double radii[4] = {0.25, 0.5, 0.75, 0.9};
    for (int i = 0; i < kCells * kFine; ++i)
        for (int j = 0; j < kCells * kFine; ++j) {
            const glm::dvec2 p = Camera::LensPoint({(i + 0.5) / (kCells * kFine), (j + 0.5) / (kCells * kFine)});
            REQUIRE(glm::length(p) <= 1 + 1e-12);
            for (int k = 0; k < 4; ++k) inside[k] += glm::length(p) <= radii[k];
        }
    for (int k = 0; k < 4; ++k)
        CHECK(double(inside[k]) / (kCells * kFine * kCells * kFine) == Approx(radii[k] * radii[k]).margin(6e-3));
}
