// bench/bounds_bench.cpp: how tight affine, reduced affine and interval bounds of every shader in
// shaders/ are, and what they cost, as Markdown tables (docs/bounds.md is this program's output).
//  - The main table: for each shader and region width, the mean widths of the affine, reduced
//    affine and interval bounds of P' over random square regions, their ratios, and the cost of
//    one bounded evaluation relative to one scalar evaluation of the same program at a point.
//  - --capacity-study: the same affine widths and costs under different Affine capacities, to pick
//    Affine::kCapacity from.
// Usage: affray_bench_bounds [--seconds S] [--regions N] [--shader NAME] [--widths 1,8,64,512]
//                            [--capacity-study [--capacities 4,6,8,...]]      (Release builds only)
// (--widths: the region widths of the main table, as denominators: 8 is 1/8.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bound_measure.h"

using namespace affray;
using affray::bench::BenchShader;

namespace {

using Corners = std::vector<std::pair<double, double>>;

struct Options {
    double seconds = 0.5;  // per rate in each measurement
    int regions = 200;
    std::string shader;  // empty: every shader
    bool capacityStudy = false;
    std::vector<int> capacities = {4, 6, 8, 10, 12, 16, 24, 32};
    std::vector<int> widths = {1, 8, 64, 512};  // main table region widths, as denominators
};

// Points of the sampled reference range, per side of a region.
constexpr int kSampleGrid = 17;
// Random points for the scalar rate.
constexpr int kScalarPoints = 1024;

/// b/a for two mean widths: how many times wider b is. Two exact bounds (both 0) are equal.
double Ratio(double a, double b) { return a == 0 && b == 0 ? 1.0 : b / a; }

std::string WidthLabel(double w) { return w == 1 ? "1" : "1/" + std::to_string(std::lround(1 / w)); }

double GeoMean(const std::vector<double>& v) {
    double s = 0;
    int n = 0;
    for (double x : v)
        if (std::isfinite(x) && x > 0) s += std::log(x), ++n;
    return n ? std::exp(s / n) : NAN;
}

double Median(std::vector<double> v) {
    std::erase_if(v, [](double x) { return !std::isfinite(x); });
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// One row of the main table: one shader at one region width.
struct Row {
    std::string shader;
    double width = 0;
    int regions = 0, unboundedA = 0, unboundedI = 0, unboundedR = 0, compared = 0;
    // Means over the regions every mode bounds (R: reduced affine).
    double boxA = 0, boxI = 0, boxR = 0, zA = 0, zI = 0, zR = 0, diagA = 0, diagI = 0, diagR = 0, zSampled = 0;
    double costA = 0, costI = 0, costR = 0;  // bounded evaluation time / scalar evaluation time
};

/// S, A, I, R: the scalar, affine, interval and reduced affine types the renderer would use for
/// this program.
template <class S, class A, class I, class R>
Row MeasureRow(const BenchShader& s, double width, const Corners& corners, const Corners& points, double seconds) {
    Row row;
    row.shader = s.name;
    row.width = width;
    row.regions = static_cast<int>(corners.size());
    std::vector<bench::RegionWidths> a = bench::BoundWidths<A>(s, corners, width);
    std::vector<bench::RegionWidths> i = bench::BoundWidths<I>(s, corners, width);
    std::vector<bench::RegionWidths> r = bench::BoundWidths<R>(s, corners, width);
    std::vector<double> sampled = bench::SampledZWidths<S>(s, corners, width, kSampleGrid);
    for (size_t k = 0; k < corners.size(); ++k) {
        row.unboundedA += !a[k].bounded;
        row.unboundedI += !i[k].bounded;
        row.unboundedR += !r[k].bounded;
        // Unbounded regions are counted, never averaged in: the means compare like with like.
        if (!a[k].bounded || !i[k].bounded || !r[k].bounded) continue;
        row.compared++;
        row.boxA += a[k].box, row.boxI += i[k].box, row.boxR += r[k].box;
        row.zA += a[k].z, row.zI += i[k].z, row.zR += r[k].z;
        row.diagA += a[k].diag, row.diagI += i[k].diag, row.diagR += r[k].diag;
        row.zSampled += sampled[k];
    }
    for (double* m : {&row.boxA, &row.boxI, &row.boxR, &row.zA, &row.zI, &row.zR, &row.diagA, &row.diagI, &row.diagR,
                      &row.zSampled})
        *m = row.compared ? *m / row.compared : NAN;
    std::vector<double> rates = bench::InterleavedRates(
        seconds, {bench::Evaluator<S>(s, points, 0.0), bench::Evaluator<A>(s, corners, width),
                  bench::Evaluator<I>(s, corners, width), bench::Evaluator<R>(s, corners, width)});
    row.costA = rates[0] / rates[1];
    row.costI = rates[0] / rates[2];
    row.costR = rates[0] / rates[3];
    return row;
}

Row Measure(const BenchShader& s, double width, const Corners& corners, const Corners& points, double seconds) {
    using vm::Affine, vm::Dual, vm::Interval, vm::ReducedAffine;
    if (s.derivatives)
        return MeasureRow<Dual<double>, Dual<Affine>, Dual<Interval>, Dual<ReducedAffine>>(s, width, corners, points,
                                                                                           seconds);
    return MeasureRow<double, Affine, Interval, ReducedAffine>(s, width, corners, points, seconds);
}

Corners CornersFor(double width, int count) {
    // One seed per width, the same for every shader and mode.
    return bench::RegionCorners(width, count, 1000 + std::lround(1 / width));
}

void PrintMainTable(const std::vector<BenchShader>& shaders, const Options& opt) {
    std::printf(
        "Widths are hi - lo of ranges of the displaced P over square (u,v) regions of the unit square "
        "P = (u, v, 0), N = (0, 0, 1): *box* is the mean over x, y, z of each component's width, *z* the "
        "width of z alone (the displacement along N), *diag* the width of (x + y + z)/sqrt(3) computed in "
        "the bound's own arithmetic (as the intersector's ray-frame measures are). Each figure is the mean "
        "over %d regions at random positions (the same for every shader and mode) that every mode bounds; "
        "*unb A/I/R* counts the regions whose affine/interval/reduced affine bound is unbounded (left out of "
        "the means). *I/A* is interval width / affine width (> 1: affine tighter), *R/A* reduced affine width "
        "/ affine width (> 1: reduced looser). *A/smp* is the affine z width over "
        "the z range sampled at %dx%d points per region (a lower bound of the true range). *cost* is the "
        "time of one bounded evaluation over the time of one scalar (double) evaluation at a point, "
        "measured interleaved in this process for %.2f s each.\n\n",
        opt.regions, kSampleGrid, kSampleGrid, opt.seconds);
    std::printf(
        "| shader | width | unb A/I/R | box A | box I | box I/A | z A | z I | z R | z I/A | z R/A | diag I/A | "
        "diag R/A | z A/smp | cost A | cost I | cost R |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    const Corners points = bench::RegionCorners(0.0, kScalarPoints, 1);
    std::vector<double> widths;
    for (int d : opt.widths) widths.push_back(1.0 / d);
    std::vector<Row> rows;
    for (const BenchShader& s : shaders)
        for (double w : widths) {
            Row r = Measure(s, w, CornersFor(w, opt.regions), points, opt.seconds);
            std::printf(
                "| %s | %s | %d/%d/%d | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | %.3g | "
                "%.3g | %.1f | %.1f | %.1f |\n",
                r.shader.c_str(), WidthLabel(w).c_str(), r.unboundedA, r.unboundedI, r.unboundedR, r.boxA, r.boxI,
                Ratio(r.boxA, r.boxI), r.zA, r.zI, r.zR, Ratio(r.zA, r.zI), Ratio(r.zA, r.zR), Ratio(r.diagA, r.diagI),
                Ratio(r.diagA, r.diagR), Ratio(r.zSampled, r.zA), r.costA, r.costI, r.costR);
            std::fflush(stdout);
            rows.push_back(r);
        }

    std::printf("\nBy width, over the shaders (geometric means of the ratios; medians of the costs):\n\n");
    std::printf(
        "| width | box I/A | z I/A | z I/A min..max | z R/A | z R/A min..max | diag I/A | diag R/A | z A/smp | "
        "cost A | cost I | cost R | cost A/I | cost R/I | unb A/I/R |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (double w : widths) {
        std::vector<double> box, z, zR, diag, diagR, smp, costA, costI, costR, costAI, costRI;
        int unbA = 0, unbI = 0, unbR = 0, total = 0;
        for (const Row& r : rows) {
            if (r.width != w) continue;
            box.push_back(Ratio(r.boxA, r.boxI));
            z.push_back(Ratio(r.zA, r.zI));
            zR.push_back(Ratio(r.zA, r.zR));
            diag.push_back(Ratio(r.diagA, r.diagI));
            diagR.push_back(Ratio(r.diagA, r.diagR));
            smp.push_back(Ratio(r.zSampled, r.zA));
            costA.push_back(r.costA);
            costI.push_back(r.costI);
            costR.push_back(r.costR);
            costAI.push_back(r.costA / r.costI);
            costRI.push_back(r.costR / r.costI);
            unbA += r.unboundedA, unbI += r.unboundedI, unbR += r.unboundedR, total += r.regions;
        }
        auto [zMin, zMax] = std::minmax_element(z.begin(), z.end());
        auto [zRMin, zRMax] = std::minmax_element(zR.begin(), zR.end());
        std::printf(
            "| %s | %.3g | %.3g | %.3g..%.3g | %.3g | %.3g..%.3g | %.3g | %.3g | %.3g | %.1f | %.1f | %.1f | "
            "%.1f | %.1f | %d/%d/%d of %d |\n",
            WidthLabel(w).c_str(), GeoMean(box), GeoMean(z), *zMin, *zMax, GeoMean(zR), *zRMin, *zRMax, GeoMean(diag),
            GeoMean(diagR), GeoMean(smp), Median(costA), Median(costI), Median(costR), Median(costAI), Median(costRI),
            unbA, unbI, unbR, total);
    }
}

/// Affine z widths and costs of one shader at one width, for each capacity.
struct CapacityRow {
    std::string shader;
    std::vector<double> z, diag, cost;
    std::vector<int> unbounded;
};

template <class S, class A>
CapacityRow MeasureCapacities(const BenchShader& s, double width, const Corners& corners, const Corners& points,
                              const Options& opt) {
    CapacityRow row;
    row.shader = s.name;
    for (int c : opt.capacities) {
        vm::Affine::SetCapacity(c);
        std::vector<bench::RegionWidths> a = bench::BoundWidths<A>(s, corners, width);
        double z = 0, diag = 0;
        int n = 0;
        for (const bench::RegionWidths& r : a)
            if (r.bounded) z += r.z, diag += r.diag, ++n;
        row.z.push_back(n ? z / n : NAN);
        row.diag.push_back(n ? diag / n : NAN);
        row.unbounded.push_back(static_cast<int>(a.size()) - n);
        std::vector<double> rates = bench::InterleavedRates(
            opt.seconds, {bench::Evaluator<S>(s, points, 0.0), bench::Evaluator<A>(s, corners, width)});
        row.cost.push_back(rates[0] / rates[1]);
    }
    vm::Affine::SetCapacity(vm::Affine::kCapacity);
    return row;
}

void PrintCapacityStudy(const std::vector<BenchShader>& shaders, const Options& opt) {
    const std::vector<int>& caps = opt.capacities;
    const size_t widest = std::max_element(caps.begin(), caps.end()) - caps.begin();
    const auto defaultIt = std::find(caps.begin(), caps.end(), vm::Affine::kCapacity);
    const Corners points = bench::RegionCorners(0.0, kScalarPoints, 1);
    std::printf(
        "Affine bounds under each capacity (terms a form keeps, eps_u and eps_v included), at region widths "
        "1/8 and 1/64, %d regions each (the same as in the main table). *rel z* is the mean z width "
        "divided by the mean z width at capacity %d (1 = as tight; > 1 looser), *rel diag* the same for "
        "(x + y + z)/sqrt(3); geometric means over the shaders, and the worst shader. *cost* is the "
        "median over the shaders of affine time / scalar time; *cost/default* the geometric mean of "
        "each shader's cost relative to its cost at capacity %d. %.2f s per rate.\n\n",
        opt.regions, caps[widest], vm::Affine::kCapacity, opt.seconds);
    const double widths[] = {1.0 / 8, 1.0 / 64};
    std::vector<CapacityRow> rows[2];
    for (int k = 0; k < 2; ++k)
        for (const BenchShader& s : shaders) {
            const Corners corners = CornersFor(widths[k], opt.regions);
            rows[k].push_back(
                s.derivatives
                    ? MeasureCapacities<vm::Dual<double>, vm::Dual<vm::Affine>>(s, widths[k], corners, points, opt)
                    : MeasureCapacities<double, vm::Affine>(s, widths[k], corners, points, opt));
        }
    std::printf("| capacity | width | rel z | worst rel z | rel diag | cost | cost/default | unbounded |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (size_t c = 0; c < caps.size(); ++c)
        for (int k = 0; k < 2; ++k) {
            std::vector<double> z, diag, cost, costRel;
            double worst = 0;
            std::string worstShader;
            int unbounded = 0;
            for (const CapacityRow& r : rows[k]) {
                double rel = Ratio(r.z[widest], r.z[c]);
                z.push_back(rel);
                diag.push_back(Ratio(r.diag[widest], r.diag[c]));
                if (rel > worst) worst = rel, worstShader = r.shader;
                cost.push_back(r.cost[c]);
                if (defaultIt != caps.end()) costRel.push_back(r.cost[c] / r.cost[defaultIt - caps.begin()]);
                unbounded += r.unbounded[c];
            }
            std::printf("| %d | %s | %.4f | %.4f (%s) | %.4f | %.1f | %.2f | %d |\n", caps[c],
                        WidthLabel(widths[k]).c_str(), GeoMean(z), worst, worstShader.c_str(), GeoMean(diag),
                        Median(cost), GeoMean(costRel), unbounded);
        }
    // Per shader: which ones need many symbols, and what keeping them costs those.
    for (int k = 0; k < 2; ++k) {
        std::printf("\nrel z (cost/default) per shader at width %s:\n\n| shader |", WidthLabel(widths[k]).c_str());
        for (int c : caps) std::printf(" %d |", c);
        std::printf("\n|---|");
        for (size_t c = 0; c < caps.size(); ++c) std::printf("---|");
        std::printf("\n");
        for (const CapacityRow& r : rows[k]) {
            std::printf("| %s |", r.shader.c_str());
            for (size_t c = 0; c < caps.size(); ++c) {
                double costRel = defaultIt == caps.end() ? NAN : r.cost[c] / r.cost[defaultIt - caps.begin()];
                std::printf(" %.4f (%.2f) |", Ratio(r.z[widest], r.z[c]), costRel);
            }
            std::printf("\n");
        }
    }
}

/// shaders/*.sl (or just `only`), sorted by name, compiled; false after printing a diagnostic.
bool LoadShaders(const std::string& only, std::vector<BenchShader>* out) {
    std::vector<std::filesystem::path> paths;
    for (const auto& e : std::filesystem::directory_iterator(std::string(AFFRAY_SOURCE_DIR) + "/shaders"))
        if (e.path().extension() == ".sl" && (only.empty() || e.path().stem() == only)) paths.push_back(e.path());
    std::sort(paths.begin(), paths.end());
    if (paths.empty()) {
        std::fprintf(stderr, "no shader %s in %s/shaders\n", only.c_str(), AFFRAY_SOURCE_DIR);
        return false;
    }
    for (const auto& p : paths) {
        // The surface shaders (the standard surfaces) have no bound to measure.
        if (compiler::CompileResult r = compiler::CompileFile(p.string());
            r.ok() && r.shader->kind != lang::ShaderKind::Displacement)
            continue;
        std::string error;
        std::optional<BenchShader> s = bench::LoadBenchShader(p.string(), &error);
        if (!s) {
            std::fprintf(stderr, "%s: %s", p.c_str(), error.c_str());
            return false;
        }
        out->push_back(std::move(*s));
    }
    return true;
}

std::vector<int> ParseList(const char* s) {
    std::vector<int> out;
    for (const char* p = s; *p;) {
        out.push_back(std::stoi(p));
        p = std::strchr(p, ',');
        if (!p) break;
        ++p;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    Options opt;
    for (int i = 1; i < argc; ++i) {
        auto arg = [&](const char* name) { return !std::strcmp(argv[i], name) && i + 1 < argc; };
        if (arg("--seconds"))
            opt.seconds = std::stod(argv[++i]);
        else if (arg("--regions"))
            opt.regions = std::max(1, std::stoi(argv[++i]));
        else if (arg("--shader"))
            opt.shader = argv[++i];
        else if (arg("--capacities"))
            opt.capacities = ParseList(argv[++i]);
        else if (arg("--widths"))
            opt.widths = ParseList(argv[++i]);
        else if (!std::strcmp(argv[i], "--capacity-study"))
            opt.capacityStudy = true;
        else {
            std::fprintf(stderr,
                         "usage: %s [--seconds S] [--regions N] [--shader NAME] [--widths 1,8,64,512] "
                         "[--capacity-study [--capacities 4,6,8,...]]\n",
                         argv[0]);
            return 2;
        }
    }
    for (int c : opt.capacities)
        if (c < 2 || c > vm::Affine::kMaxCapacity) {
            std::fprintf(stderr, "capacity %d outside [2, %d]\n", c, vm::Affine::kMaxCapacity);
            return 2;
        }
    for (int d : opt.widths)
        if (d < 1) {
            std::fprintf(stderr, "--widths: %d is not a width denominator >= 1\n", d);
            return 2;
        }
    if (opt.widths.empty()) {
        std::fprintf(stderr, "--widths: no width given\n");
        return 2;
    }
    if (opt.capacities.empty()) {
        std::fprintf(stderr, "--capacities: no capacity given\n");
        return 2;
    }
    std::vector<BenchShader> shaders;
    if (!LoadShaders(opt.shader, &shaders)) return 1;
    if (opt.capacityStudy)
        PrintCapacityStudy(shaders, opt);
    else
        PrintMainTable(shaders, opt);
    return 0;
}
