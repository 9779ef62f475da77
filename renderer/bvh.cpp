// renderer/bvh.cpp: the slab test, and building the top-level hierarchy (renderer/bvh.h): the
// binned surface-area heuristic, the median split it falls back on, the parallel top levels and
// the copy of the subtrees into one vector.
#include "renderer/bvh.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <numeric>

#include "renderer/thread_pool.h"

namespace affray::renderer {

bool Box::Clip(const Ray& ray, double* t0, double* t1) const {
    if (empty()) return false;
    double lo = *t0, hi = *t1;
    for (int i = 0; i < 3; ++i) {
        const double o = ray.origin[i], d = ray.dir[i];
        if (d == 0) {
            if (o < this->lo[i] || o > this->hi[i]) return false;
            continue;
        }
        // Infinite box sides give infinite slab ends, which is right: a box unbounded along an
        // axis limits nothing there. 0 * inf cannot occur: d != 0.
        double a = (this->lo[i] - o) / d, b = (this->hi[i] - o) / d;
        if (a > b) std::swap(a, b);
        // The subtraction and division each round by half an ulp: widen by a few.
        if (std::isfinite(a)) a -= 4e-16 * std::fabs(a) + 1e-300;
        if (std::isfinite(b)) b += 4e-16 * std::fabs(b) + 1e-300;
        lo = std::max(lo, a);
        hi = std::min(hi, b);
        if (lo > hi) return false;
    }
    *t0 = lo;
    *t1 = hi;
    return true;
}

Bvh::FloatBox Bvh::FloatBox::FromBox(const Box& b) {
    // Rounded outwards (infinite sides stay infinite; a side past float's range is the infinity
    // beyond it or float's largest on its side, whichever keeps the box a superset: converting
    // such a double is undefined).
    auto down = [](double x) {
        if (x > FLT_MAX) return FLT_MAX;
        if (!(x >= -FLT_MAX)) return -INFINITY;
        const float f = static_cast<float>(x);
        return double(f) > x ? std::nextafter(f, -INFINITY) : f;
    };
    auto up = [](double x) {
        if (x < -FLT_MAX) return -FLT_MAX;
        if (!(x <= FLT_MAX)) return INFINITY;
        const float f = static_cast<float>(x);
        return double(f) < x ? std::nextafter(f, INFINITY) : f;
    };
    FloatBox f;
    for (int i = 0; i < 3; ++i) {
        f.lo[i] = down(b.lo[i]);
        f.hi[i] = up(b.hi[i]);
    }
    return f;
}

namespace {

constexpr int kBins = 16;
// A range of at least this many primitives is binned on all the pool's threads, in chunks.
constexpr int kParallelBinItems = 1 << 15;
constexpr int kBinChunk = 1 << 13;
// Subtrees built on their own are at least this big (smaller ones are not worth a task).
constexpr size_t kMinTaskItems = 1 << 10;

/// The depth of the tree that median splits build over n primitives (leaves of kLeafPrimitives).
int MedianHeight(size_t n) {
    int h = 0;
    for (; n > size_t(Bvh::kLeafPrimitives); n -= n / 2) ++h;
    return h;
}

}  // namespace

/// The build: the primitives' indices and float boxes (m_items, m_itemBoxes), permuted in place so
/// that every node's primitives are a range of them, and the steps that split a range.
struct Bvh::Builder {
    static constexpr FloatBox kEmpty{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    static void Join(FloatBox* box, const FloatBox& b) {
        for (int i = 0; i < 3; ++i) {
            box->lo[i] = std::min(box->lo[i], b.lo[i]);
            box->hi[i] = std::max(box->hi[i], b.hi[i]);
        }
    }
    /// A range's box (the union of its primitives' boxes) and the bounds of their centres.
    struct Bounds {
        FloatBox box = kEmpty;
        glm::dvec3 cLo{INFINITY}, cHi{-INFINITY};
        void Extend(const FloatBox& b, const glm::dvec3& centre) {
            Join(&box, b);
            cLo = glm::min(cLo, centre);
            cHi = glm::max(cHi, centre);
        }
    };
    struct Bin {
        FloatBox box = kEmpty;
        int count = 0;
    };
    /// A range's bins along each axis, and how a centre's coordinate maps to a bin.
    struct Binning {
        std::array<std::array<Bin, kBins>, 3> bins;
        double lo[3], scale[3];
        bool usable[3];
        int BinOf(double c, int axis) const {
            // c >= lo and c - lo <= the extent: the product is in [0, kBins], kBins only by rounding.
            return std::clamp(static_cast<int>((c - lo[axis]) * scale[axis]), 0, kBins - 1);
        }
    };
    /// A range of m_items still to be split, at `depth` in the tree.
    struct Range {
        int begin, end, depth;
        Bounds bounds;
    };

    Bvh& bvh;
    ThreadPool* pool;
    Split split;

    /// The centre of b along `axis`, where binning and the median place it. A box infinite along
    /// the axis has no centre there: its finite side stands in, or 0.
    static double Centre(const FloatBox& b, int axis) {
        const double c = 0.5 * double(b.lo[axis]) + 0.5 * double(b.hi[axis]);
        if (std::isfinite(c)) return c;
        if (std::isfinite(b.lo[axis])) return b.lo[axis];
        return std::isfinite(b.hi[axis]) ? b.hi[axis] : 0.0;
    }
    static glm::dvec3 Centre(const FloatBox& b) { return {Centre(b, 0), Centre(b, 1), Centre(b, 2)}; }

    /// Half the surface area of b: 0 if it is empty, infinite if it is (0 x infinity included).
    static double Area(const FloatBox& b) {
        double d[3];
        for (int i = 0; i < 3; ++i) {
            d[i] = double(b.hi[i]) - double(b.lo[i]);
            if (d[i] < 0) return 0;
        }
        const double a = d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
        return std::isnan(a) ? INFINITY : a;
    }

    /// The bounds of m_items[begin .. end).
    Bounds BoundsOf(int begin, int end) {
        Bounds b;
        for (int i = begin; i < end; ++i) b.Extend(bvh.m_itemBoxes[size_t(i)], Centre(bvh.m_itemBoxes[size_t(i)]));
        return b;
    }

    /// A node over `bounds`; its box's zeros made positive, so that the same tree is the same bits
    /// whatever order its boxes were merged in (min(-0, +0) is either).
    static Node NodeOver(const Bounds& bounds) {
        Node node{bounds.box};
        for (int i = 0; i < 3; ++i) {
            node.box.lo[i] += 0.0f;
            node.box.hi[i] += 0.0f;
        }
        return node;
    }

    /// Swaps primitives i and j (their indices and boxes).
    void Swap(int i, int j) {
        std::swap(bvh.m_items[size_t(i)], bvh.m_items[size_t(j)]);
        std::swap(bvh.m_itemBoxes[size_t(i)], bvh.m_itemBoxes[size_t(j)]);
    }

    /// Adds m_items[begin .. end) to `out`'s bins.
    void BinInto(int begin, int end, Binning* out) {
        for (int i = begin; i < end; ++i) {
            const FloatBox& b = bvh.m_itemBoxes[size_t(i)];
            const glm::dvec3 c = Centre(b);
            for (int axis = 0; axis < 3; ++axis) {
                if (!out->usable[axis]) continue;
                Bin& bin = out->bins[size_t(axis)][size_t(out->BinOf(c[axis], axis))];
                Join(&bin.box, b);
                ++bin.count;
            }
        }
    }

    /// Splits r by the binned SAH: partitions its primitives in place and returns the first of the
    /// right child's, with the children's bounds; -1 (nothing moved) if no split separates the
    /// centres at a finite cost within the depth limit. Bins on the pool's threads if `parallel`.
    int SplitSah(const Range& r, bool parallel, Binning* binning, Bounds* left, Bounds* right) {
        Binning& bn = *binning;
        bool any = false;
        for (int axis = 0; axis < 3; ++axis) {
            const double extent = r.bounds.cHi[axis] - r.bounds.cLo[axis];
            bn.usable[axis] = extent > 0 && std::isfinite(extent);
            bn.lo[axis] = r.bounds.cLo[axis];
            bn.scale[axis] = bn.usable[axis] ? kBins / extent : 0;
            any = any || bn.usable[axis];
            for (Bin& bin : bn.bins[size_t(axis)]) bin = Bin();
        }
        if (!any) return -1;  // every centre at one point
        if (parallel) {
            // Each thread bins chunks into its own bins, merged after: counts add and boxes join
            // exactly, in any order, so the bins are those of a serial pass.
            std::vector<Binning> perThread(size_t(pool->size()), bn);
            const int n = r.end - r.begin;
            pool->ForEach(size_t((n + kBinChunk - 1) / kBinChunk), [&](size_t chunk, int worker) {
                const int begin = r.begin + int(chunk) * kBinChunk;
                BinInto(begin, std::min(r.end, begin + kBinChunk), &perThread[size_t(worker)]);
            });
            for (const Binning& t : perThread)
                for (size_t axis = 0; axis < 3; ++axis)
                    for (size_t k = 0; k < kBins; ++k) {
                        Join(&bn.bins[axis][k].box, t.bins[axis][k].box);
                        bn.bins[axis][k].count += t.bins[axis][k].count;
                    }
        } else {
            BinInto(r.begin, r.end, &bn);
        }

        // The least cost over the planes between bins, on every axis: sweep the right sides'
        // costs from the last bin, then the left sides' from the first. A split is allowed only
        // if median splits below it end within the depth limit.
        double bestCost = INFINITY;
        int bestAxis = -1, bestBin = -1;
        for (int axis = 0; axis < 3; ++axis) {
            if (!bn.usable[axis]) continue;
            const auto& bins = bn.bins[size_t(axis)];
            double rightCost[kBins];
            int rightCount[kBins];
            FloatBox acc = kEmpty;
            int count = 0;
            for (int k = kBins - 1; k > 0; --k) {
                Join(&acc, bins[size_t(k)].box);
                count += bins[size_t(k)].count;
                rightCount[k] = count;
                rightCost[k] = count > 0 ? Area(acc) * count : 0;
            }
            acc = kEmpty;
            count = 0;
            for (int k = 0; k < kBins - 1; ++k) {
                Join(&acc, bins[size_t(k)].box);
                count += bins[size_t(k)].count;
                if (count == 0 || rightCount[k + 1] == 0) continue;
                if (r.depth + 1 + MedianHeight(size_t(std::max(count, rightCount[k + 1]))) > kMaxDepth) continue;
                const double cost = Area(acc) * count + rightCost[k + 1];
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = k;
                }
            }
        }
        if (bestAxis < 0) return -1;

        // Partition by the same BinOf that binned, so that each primitive lands on its bin's side,
        // and gather the children's bounds on the way (each primitive is looked at once, but for
        // the one where the two scans meet).
        *left = Bounds();
        *right = Bounds();
        const std::vector<FloatBox>& boxes = bvh.m_itemBoxes;
        auto isLeft = [&](const glm::dvec3& c) { return bn.BinOf(c[bestAxis], bestAxis) <= bestBin; };
        int i = r.begin, j = r.end - 1;
        for (;;) {
            glm::dvec3 ci, cj;
            while (i <= j && isLeft(ci = Centre(boxes[size_t(i)]))) left->Extend(boxes[size_t(i++)], ci);
            while (i <= j && !isLeft(cj = Centre(boxes[size_t(j)]))) right->Extend(boxes[size_t(j--)], cj);
            if (i >= j) break;
            Swap(i, j);
            left->Extend(boxes[size_t(i++)], cj);
            right->Extend(boxes[size_t(j--)], ci);
        }
        return i;
    }

    /// Splits r at the median of its centres along their longest axis: partitions in place so that
    /// the smaller half of the centres comes first (ties in the order met) and returns the middle,
    /// with the children's bounds. `keys` is scratch.
    int SplitMedian(const Range& r, std::vector<double>* keys, Bounds* left, Bounds* right) {
        const glm::dvec3 extent = r.bounds.cHi - r.bounds.cLo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const int mid = r.begin + (r.end - r.begin) / 2;
        keys->clear();
        for (int i = r.begin; i < r.end; ++i) keys->push_back(Centre(bvh.m_itemBoxes[size_t(i)], axis));
        std::nth_element(keys->begin(), keys->begin() + (mid - r.begin), keys->end());
        const double median = (*keys)[size_t(mid - r.begin)];
        // Three ways (less, equal, greater): fewer than half are less and more than half are at
        // most the median, so the middle falls among the equal ones.
        int less = r.begin, i = r.begin, greater = r.end;
        while (i < greater) {
            const double c = Centre(bvh.m_itemBoxes[size_t(i)], axis);
            if (c < median) {
                Swap(i++, less++);
            } else if (c > median) {
                Swap(i, --greater);
            } else {
                ++i;
            }
        }
        *left = BoundsOf(r.begin, mid);
        *right = BoundsOf(mid, r.end);
        return mid;
    }

    /// Splits r (more than kLeafPrimitives primitives) by the build's rule; returns the middle.
    int SplitRange(const Range& r, bool parallel, Binning* binning, std::vector<double>* keys, Bounds* left,
                   Bounds* right) {
        if (split == Split::kSah) {
            const int mid = SplitSah(r, parallel, binning, left, right);
            if (mid >= 0) return mid;
        }
        return SplitMedian(r, keys, left, right);
    }

    /// Builds the subtree over r into `out` in preorder (a node, its left subtree, its right);
    /// returns its root's index there.
    int BuildSerial(const Range& r, std::vector<Node>* out, Binning* binning, std::vector<double>* keys) {
        const int index = static_cast<int>(out->size());
        out->push_back(NodeOver(r.bounds));
        if (r.end - r.begin <= kLeafPrimitives) {
            (*out)[size_t(index)].a = r.begin;
            (*out)[size_t(index)].b = r.begin - r.end;
            return index;
        }
        Range left{r.begin, 0, r.depth + 1, {}}, right{0, r.end, r.depth + 1, {}};
        left.end = right.begin = SplitRange(r, false, binning, keys, &left.bounds, &right.bounds);
        const int a = BuildSerial(left, out, binning, keys);
        const int b = BuildSerial(right, out, binning, keys);
        (*out)[size_t(index)].a = a;
        (*out)[size_t(index)].b = b;
        return index;
    }

    /// Splits r on the calling thread (binning big ranges on the pool) down to ranges of at most
    /// taskItems primitives, which become `tasks`. `top` gets r's nodes in preorder; a task's
    /// place is a node with b == 0 and a its index in `tasks`. Returns r's index in `top`.
    int BuildTop(const Range& r, size_t taskItems, std::vector<Node>* top, std::vector<Range>* tasks, Binning* binning,
                 std::vector<double>* keys) {
        const int index = static_cast<int>(top->size());
        top->push_back(NodeOver(r.bounds));
        if (size_t(r.end - r.begin) <= taskItems) {
            (*top)[size_t(index)].a = static_cast<int>(tasks->size());
            (*top)[size_t(index)].b = 0;
            tasks->push_back(r);
            return index;
        }
        const bool parallel = pool && pool->size() > 1 && r.end - r.begin >= kParallelBinItems;
        Range left{r.begin, 0, r.depth + 1, {}}, right{0, r.end, r.depth + 1, {}};
        left.end = right.begin = SplitRange(r, parallel, binning, keys, &left.bounds, &right.bounds);
        const int a = BuildTop(left, taskItems, top, tasks, binning, keys);
        const int b = BuildTop(right, taskItems, top, tasks, binning, keys);
        (*top)[size_t(index)].a = a;
        (*top)[size_t(index)].b = b;
        return index;
    }

    /// Appends the subtree of top[t] to m_nodes in preorder, a task's nodes shifted to their place
    /// (and freed); returns its index there. This is the order BuildSerial makes over the root.
    int Emit(const std::vector<Node>& top, int t, std::vector<std::vector<Node>>* taskNodes) {
        const Node& node = top[size_t(t)];
        const int index = static_cast<int>(bvh.m_nodes.size());
        if (node.b == 0) {
            std::vector<Node>& nodes = (*taskNodes)[size_t(node.a)];
            for (Node n : nodes) {
                if (n.b > 0) {
                    n.a += index;
                    n.b += index;
                }
                bvh.m_nodes.push_back(n);
            }
            std::vector<Node>().swap(nodes);
            return index;
        }
        bvh.m_nodes.push_back(node);
        const int a = Emit(top, node.a, taskNodes);
        const int b = Emit(top, node.b, taskNodes);
        bvh.m_nodes[size_t(index)].a = a;
        bvh.m_nodes[size_t(index)].b = b;
        return index;
    }
};

Bvh::Bvh(const std::vector<Box>& boxes, ThreadPool* pool, Split split) {
    // The non-empty boxes, in floats; vectors of exactly their size.
    size_t count = 0;
    for (const Box& b : boxes) count += b.empty() ? 0 : 1;
    if (count == 0) return;
    m_items.reserve(count);
    m_itemBoxes.reserve(count);
    Builder builder{*this, pool, split};
    Builder::Range root{0, static_cast<int>(count), 0, {}};
    for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
        if (boxes[size_t(i)].empty()) continue;
        m_items.push_back(i);
        m_itemBoxes.push_back(FloatBox::FromBox(boxes[size_t(i)]));
        root.bounds.Extend(m_itemBoxes.back(), Builder::Centre(m_itemBoxes.back()));
    }

    // The top levels on this thread, down to some 4 subtrees a thread (so that big and small ones
    // even out), then the subtrees on the pool's threads, biggest first. Each worker has its own
    // scratch.
    const int threads = pool ? pool->size() : 1;
    const size_t taskItems = threads > 1 ? std::max(kMinTaskItems, count / size_t(4 * threads)) : count;
    std::vector<Builder::Binning> binnings(static_cast<size_t>(threads));
    std::vector<std::vector<double>> keys(static_cast<size_t>(threads));
    std::vector<Node> top;
    std::vector<Builder::Range> tasks;
    builder.BuildTop(root, taskItems, &top, &tasks, &binnings[0], &keys[0]);
    std::vector<size_t> order(tasks.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return tasks[a].end - tasks[a].begin > tasks[b].end - tasks[b].begin; });
    std::vector<std::vector<Node>> taskNodes(tasks.size());
    auto buildTask = [&](size_t i, int worker) {
        const size_t t = order[i];
        builder.BuildSerial(tasks[t], &taskNodes[t], &binnings[size_t(worker)], &keys[size_t(worker)]);
    };
    if (pool && tasks.size() > 1) {
        pool->ForEach(tasks.size(), buildTask);
    } else {
        for (size_t i = 0; i < tasks.size(); ++i) buildTask(i, 0);
    }

    // One vector of exactly the nodes, in the serial build's order.
    size_t nodes = top.size() - tasks.size();
    for (const std::vector<Node>& t : taskNodes) nodes += t.size();
    m_nodes.reserve(nodes);
    m_root = builder.Emit(top, 0, &taskNodes);
}

double Bvh::SahCost() const {
    if (m_root < 0) return 0;
    const double rootArea = Builder::Area(m_nodes[size_t(m_root)].box);
    if (!std::isfinite(rootArea)) return INFINITY;
    double cost = 1;  // the root's box
    for (const Node& node : m_nodes) {
        const double share = rootArea > 0 ? Builder::Area(node.box) / rootArea : 1;
        cost += share * (node.b < 0 ? -node.b : 2);
    }
    return cost;
}

int Bvh::depth() const {
    if (m_root < 0) return -1;
    auto deepest = [&](auto&& self, int node) -> int {
        const Node& n = m_nodes[size_t(node)];
        return n.b < 0 ? 0 : 1 + std::max(self(self, n.a), self(self, n.b));
    };
    return deepest(deepest, m_root);
}

}  // namespace affray::renderer
