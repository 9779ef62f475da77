// renderer/bound_tree.cpp: region bounds reduced to what a ray test needs, and the shared, lazily
// built, memory-budgeted quadtree of them (see the header).
#include "renderer/bound_tree.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <tuple>
#include <type_traits>

#include "renderer/measure.h"
#include "vm/interpreter.h"
#include "vm/prune.h"

namespace affray::renderer {

namespace {

/// x rounded up by a relative margin covering the rounding of a sum of n terms of the same sign.
double RoundedUpSum(double x, int n) { return x * (1 + 2 * (n + 2) * kUlp) + 1e-300; }

/// Coordinate i of the bound's box: `range`, or the whole line if it is unbounded.
void SetBox(const vm::Interval& range, int i, RegionBound* out) {
    out->lo[i] = range.isUnbounded() ? -INFINITY : range.lo();
    out->hi[i] = range.isUnbounded() ? INFINITY : range.hi();
}

/// The bound of one coordinate by an interval: its middle and radius.
void FromRange(const vm::Interval& range, int i, RegionBound* out) {
    SetBox(range, i, out);
    if (range.isUnbounded()) return;
    const double c = 0.5 * range.lo() + 0.5 * range.hi();
    double r = std::max(range.hi() - c, c - range.lo());
    r = r * (1 + 4 * kUlp) + 1e-300;  // each difference rounds by half an ulp at most
    if (!std::isfinite(c) || !std::isfinite(r)) return;
    out->c[i] = c;
    out->r[i] = r;
    out->boundedMask |= uint8_t(1u << i);
}

RegionBound Reduce(const vm::Vec3<vm::Interval>& p) {
    RegionBound out;
    for (int i = 0; i < 3; ++i) FromRange(p[i], i, &out);
    return out;
}

/// An affine P' reduced to c + a eps_u + b eps_v + g eps_w + [-r, r]: the terms of the other
/// symbols form a 3 x K matrix whose columns are mostly parallel for a displacement along one
/// direction; the columns close to the largest one's direction w go into the segment g (as
/// alpha_k * w, exact for any alpha_k, with the residual G_k - alpha_k w into r), the others into r.
RegionBound Reduce(const vm::Vec3<vm::Affine>& p) {
    using vm::Affine;
    RegionBound out;
    for (int i = 0; i < 3; ++i) SetBox(p[i].range(), i, &out);
    // Gather the columns of the other symbols, merging the three sorted term lists.
    constexpr int kMax = 3 * Affine::kMaxCapacity;
    double cols[kMax][3];
    int k = 0;
    int next[3] = {0, 0, 0};
    for (;;) {
        Affine::SymbolId lowest = ~Affine::SymbolId(0);
        for (int i = 0; i < 3; ++i)
            if (!p[i].isUnbounded() && next[i] < p[i].termCount()) lowest = std::min(lowest, p[i].termSymbol(next[i]));
        if (lowest == ~Affine::SymbolId(0)) break;
        double col[3] = {0, 0, 0};
        for (int i = 0; i < 3; ++i)
            if (!p[i].isUnbounded() && next[i] < p[i].termCount() && p[i].termSymbol(next[i]) == lowest)
                col[i] = p[i].termCoef(next[i]++);
        if (lowest == Affine::kSymbolU || lowest == Affine::kSymbolV) {
            for (int i = 0; i < 3; ++i) (lowest == Affine::kSymbolU ? out.a : out.b)[i] = col[i];
            continue;
        }
        for (int i = 0; i < 3; ++i) cols[k][i] = col[i];
        ++k;
    }
    // The direction of the largest column (by L1 norm) among the bounded coordinates.
    int largest = -1;
    double largestNorm = 0;
    for (int j = 0; j < k; ++j) {
        const double n = std::fabs(cols[j][0]) + std::fabs(cols[j][1]) + std::fabs(cols[j][2]);
        if (n > largestNorm) largestNorm = n, largest = j;
    }
    double r[3] = {0, 0, 0};
    double segment = 0;  // sum |alpha_k|
    glm::dvec3 w(0.0);
    if (largest >= 0) w = glm::dvec3(cols[largest][0], cols[largest][1], cols[largest][2]);
    const double ww = glm::dot(w, w);
    for (int j = 0; j < k; ++j) {
        const double* col = cols[j];
        const double norm = std::fabs(col[0]) + std::fabs(col[1]) + std::fabs(col[2]);
        double alpha = ww > 0 && std::isfinite(ww) ? (col[0] * w.x + col[1] * w.y + col[2] * w.z) / ww : 0;
        double res[3], resNorm = 0;
        for (int i = 0; i < 3; ++i) {
            res[i] = col[i] - alpha * w[i];
            resNorm += std::fabs(res[i]);
        }
        if (!std::isfinite(alpha) || !(resNorm <= 0.5 * norm)) {
            for (int i = 0; i < 3; ++i) r[i] += std::fabs(col[i]);
            continue;
        }
        // col = alpha w + res exactly up to the rounding of res, bounded by an ulp of each part.
        segment += std::fabs(alpha);
        for (int i = 0; i < 3; ++i)
            r[i] += std::fabs(res[i]) + 2 * kUlp * (std::fabs(alpha * w[i]) + std::fabs(res[i]));
    }
    segment = RoundedUpSum(segment, k);
    for (int i = 0; i < 3; ++i) {
        if (p[i].isUnbounded()) continue;
        const double g = w[i] * segment;
        const double ri = RoundedUpSum(r[i] + p[i].error() + 2 * kUlp * std::fabs(g), k + 2);
        if (!std::isfinite(g) || !std::isfinite(ri) || !std::isfinite(p[i].center())) continue;
        out.c[i] = p[i].center();
        out.g[i] = g;
        out.r[i] = ri;
        out.boundedMask |= uint8_t(1u << i);
    }
    for (int i = 0; i < 3; ++i)
        if (!(out.boundedMask & (1u << i))) out.a[i] = out.b[i] = out.g[i] = 0;
    return out;
}

/// A reduced affine P': its eps_u and eps_v coefficients, everything else in its error.
RegionBound Reduce(const vm::Vec3<vm::ReducedAffine>& p) {
    RegionBound out;
    for (int i = 0; i < 3; ++i) {
        const vm::Interval range = p[i].range();
        SetBox(range, i, &out);
        if (p[i].isUnbounded() || range.isUnbounded()) continue;
        const double c = p[i].center(), a = p[i].coefficientU(), b = p[i].coefficientV(), r = p[i].error();
        if (!std::isfinite(c + a + b + r)) continue;
        out.c[i] = c;
        out.a[i] = a;
        out.b[i] = b;
        out.r[i] = r;
        out.boundedMask |= uint8_t(1u << i);
    }
    return out;
}

template <class T>
RegionBound Reduce(const vm::Vec3<vm::Dual<T>>& p) {
    return Reduce(vm::Vec3<T>{p.x.v, p.y.v, p.z.v});
}

}  // namespace

class EvaluatorPool {
  public:
    /// A region's slopes as a thread last computed them (RegionEvaluator::Slopes), keyed by the
    /// program, the surface and the region: a function of those alone, so a kept entry is what
    /// computing them again would give, and the image does not depend on what the cache held.
    struct SlopeEntry {
        const void* program = nullptr;
        const void* surface = nullptr;
        double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
        bool filled = false, valid = false;
        SlopeBound slopes;
    };
    /// The entry of a region: the kept one, or an emptied slot now keyed by it (direct-mapped:
    /// a region takes the slot of another that hashes alike).
    SlopeEntry* FindSlopes(const void* program, const void* surface, double u0, double u1, double v0, double v1) {
        if (m_slopes.empty()) m_slopes.resize(kSlopeEntries);
        uint64_t h = std::bit_cast<uint64_t>(program) * 0x9e3779b97f4a7c15ull ^ std::bit_cast<uint64_t>(surface);
        for (double x : {u0, u1, v0, v1}) h = (h ^ std::bit_cast<uint64_t>(x)) * 0xff51afd7ed558ccdull;
        SlopeEntry& e = m_slopes[(h >> 40) % kSlopeEntries];
        if (e.program != program || e.surface != surface || e.u0 != u0 || e.u1 != u1 || e.v0 != v0 || e.v1 != v1)
            e = SlopeEntry{program, surface, u0, u1, v0, v1, false, false, {}};
        return &e;
    }

    /// The pool's interpreter for type N, first made for `program`.
    template <class N>
    std::shared_ptr<vm::Interpreter<N>> Get(const vm::Program& program) {
        std::shared_ptr<vm::Interpreter<N>>& slot = std::get<std::shared_ptr<vm::Interpreter<N>>>(m_interpreters);
        if (!slot) slot = std::make_shared<vm::Interpreter<N>>(program);
        return slot;
    }

  private:
    std::tuple<std::shared_ptr<vm::Interpreter<vm::Dual<double>>>, std::shared_ptr<vm::Interpreter<vm::Interval>>,
               std::shared_ptr<vm::Interpreter<vm::Affine>>, std::shared_ptr<vm::Interpreter<vm::ReducedAffine>>,
               std::shared_ptr<vm::Interpreter<vm::Dual<vm::Interval>>>,
               std::shared_ptr<vm::Interpreter<vm::Dual<vm::Affine>>>,
               std::shared_ptr<vm::Interpreter<vm::Dual<vm::ReducedAffine>>>>
        m_interpreters;
    static constexpr size_t kSlopeEntries = 2048;  // about 0.9 MB per thread
    std::vector<SlopeEntry> m_slopes;
};

namespace {

template <class N>
class RegionEvaluatorT final : public RegionEvaluator {
  public:
    /// With `pool` (a thread's, which must outlive this), each evaluation runs on the pool's
    /// interpreter of its type after pointing it at `program`; without, on interpreters of its own.
    RegionEvaluatorT(const BaseSurface& surface, const vm::Program& program, const glm::dvec3& eye,
                     std::shared_ptr<EvaluatorPool> pool = nullptr)
        : m_surface(surface),
          m_program(program),
          m_interp(pool ? pool->Get<N>(program) : std::make_shared<vm::Interpreter<N>>(program)),
          m_output(*program.findOutput("P")),
          m_eye(eye),
          m_pool(std::move(pool)),
          m_slopes(kPlainBound && !program.usesDerivatives() && vm::SlopesCanBound(program)),
          m_jumps(vm::HasJumps(program)) {}

    RegionBound Bound(double u0, double u1, double v0, double v1) override {
        return Reduce(EvaluateOnSurface(Interp(), m_surface, u0, u1, v0, v1, m_eye, m_output));
    }

    bool PointAt(double u, double v, glm::dvec3* p) override {
        const Vec3<N> x = EvaluateOnSurface(Interp(), m_surface, u, u, v, v, m_eye, m_output);
        for (int i = 0; i < 3; ++i) {
            const vm::Interval r = RangeOf(vm::ValueOf(x[i]));
            if (r.isUnbounded()) return false;
            (*p)[i] = r.mid();
        }
        return true;
    }

    bool slopes() const override { return m_slopes; }

    bool Slopes(double u0, double u1, double v0, double v1, SlopeBound* out) override {
        if constexpr (!kPlainBound) {
            return false;
        } else {
            if (!m_slopes) return false;
            EvaluatorPool::SlopeEntry* kept =
                m_pool ? m_pool->FindSlopes(&m_program, &m_surface, u0, u1, v0, v1) : nullptr;
            if (kept && kept->filled) {
                *out = kept->slopes;
                return kept->valid;
            }
            vm::Interpreter<vm::Dual<N>>& interp = Shared(m_dual);
            interp.SetRecording(m_jumps);
            const Vec3<vm::Dual<N>> x = EvaluateOnSurface(interp, m_surface, u0, u1, v0, v1, m_eye, m_output);
            interp.SetRecording(false);
            bool valid = !m_jumps || vm::JumpsDecided(m_program, interp.decisions());
            if (valid) {
                out->du = Reduce(Vec3<N>{x[0].du, x[1].du, x[2].du});
                out->dv = Reduce(Vec3<N>{x[0].dv, x[1].dv, x[2].dv});
                out->rate[0] = m_surface.DualRate(0);
                out->rate[1] = m_surface.DualRate(1);
                valid = out->du.bounded() && out->dv.bounded();
            }
            if (kept) {
                kept->filled = true;
                kept->valid = valid;
                kept->slopes = *out;
            }
            return valid;
        }
    }

    bool PointFrame(double u, double v, glm::dvec3* p, glm::dvec3* pu, glm::dvec3* pv) override {
        if (!m_slopes) return false;
        const Vec3<vm::Dual<double>> x = EvaluateOnSurface(Shared(m_point), m_surface, u, u, v, v, m_eye, m_output);
        const double ru = m_surface.DualRate(0), rv = m_surface.DualRate(1);
        for (int i = 0; i < 3; ++i) {
            (*p)[i] = x[i].v;
            (*pu)[i] = x[i].du / ru;
            (*pv)[i] = x[i].dv / rv;
        }
        return std::isfinite(glm::dot(*p, *p) + glm::dot(*pu, *pu) + glm::dot(*pv, *pv));
    }

  private:
    /// A bound type without derivatives of its own: only then are slopes bounded (a program that
    /// takes derivatives runs as a Dual already, and its P' needs derivatives it does not keep).
    static constexpr bool kPlainBound = !vm::NumberTraits<N>::kHasDerivatives;
    using SlopeType = std::conditional_t<kPlainBound, vm::Dual<N>, N>;

    vm::Interpreter<N>& Interp() {
        if (&m_interp->program() != &m_program) m_interp->SetProgram(m_program);
        return *m_interp;
    }
    /// The interpreter in `slot` (the pool's, or one of its own made on first use), running m_program.
    template <class M>
    vm::Interpreter<M>& Shared(std::shared_ptr<vm::Interpreter<M>>& slot) {
        if (!slot) slot = m_pool ? m_pool->Get<M>(m_program) : std::make_shared<vm::Interpreter<M>>(m_program);
        if (&slot->program() != &m_program) slot->SetProgram(m_program);
        return *slot;
    }

    const BaseSurface& m_surface;
    const vm::Program& m_program;
    std::shared_ptr<vm::Interpreter<N>> m_interp;
    const vm::ProgramOutput& m_output;
    glm::dvec3 m_eye;
    std::shared_ptr<EvaluatorPool> m_pool;  // null: interpreters of its own
    bool m_slopes = false, m_jumps = false;
    std::shared_ptr<vm::Interpreter<SlopeType>> m_dual;
    std::shared_ptr<vm::Interpreter<vm::Dual<double>>> m_point;
};

}  // namespace

std::shared_ptr<EvaluatorPool> MakeEvaluatorPool() { return std::make_shared<EvaluatorPool>(); }

int SplitAxis(const RegionBound& b, int levelU, int levelV, int maxDepth) {
    if (levelU >= maxDepth) return kSplitV;
    if (levelV >= maxDepth) return kSplitU;
    const int balanced = levelU == levelV ? kSplitBoth : levelU < levelV ? kSplitU : kSplitV;
    // The first two levels split both ways: a region spanning half a turn or more of a periodic
    // parameter (a sphere's u) has a linear part near 0 along it however far it stretches.
    if (!b.bounded() || std::abs(levelU - levelV) >= kMaxImbalance || std::min(levelU, levelV) < 2) return balanced;
    // Twice as long: four times the squared length. Generators dwarfed by the rest of the bound
    // (the segment and the box: a region whose form has lost its slopes to its error) say
    // nothing of the shape: split both ways.
    const double a2 = glm::dot(b.a, b.a), b2 = glm::dot(b.b, b.b);
    if (!std::isfinite(a2 + b2)) return balanced;
    if (std::max(a2, b2) < glm::dot(b.g, b.g) + glm::dot(b.r, b.r)) return balanced;
    if (a2 > 4 * b2) return kSplitU;
    if (b2 > 4 * a2) return kSplitV;
    return balanced;
}

void CacheBudget::Add(uint64_t n) {
    const uint64_t now = bytes.fetch_add(n, std::memory_order_relaxed) + n;
    uint64_t peak = peakBytes.load(std::memory_order_relaxed);
    while (now > peak && !peakBytes.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {}
}

void CacheBudget::SetOwner(TreeOwner* owner) {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_owner = owner;
}

void CacheBudget::Enforce() {
    std::unique_lock<std::mutex> lock(m_mutex, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is at it
    // What earlier passes retired and no ray holds any more goes first.
    std::erase_if(m_retiring, [](BoundTree* tree) {
        tree->Reclaim();
        return tree->m_retired.empty();
    });
    // Blocks retired but still held by rays under way are freed at a later pass, and trees
    // retired once their owner frees them; evicting more for them would not free them sooner.
    const uint64_t live = bytes.load(std::memory_order_relaxed) - m_retiredBytes.load(std::memory_order_relaxed);
    if (live <= limit) return;
    m_passes.fetch_add(1, std::memory_order_relaxed);
    // Down to half the budget, what was used longest ago first, whichever tree holds it: blocks
    // by the stamp of the node they expand, idle trees (no walker holds them) by the last ray
    // that entered them; a tree made or entered since the clock last ticked stays.
    const uint64_t excess = live - limit / 2;
    const uint32_t now = m_clock.load(std::memory_order_relaxed);
    std::vector<uint32_t> stamps;
    for (BoundTree* tree : m_trees) tree->CollectStamps(&stamps);
    std::vector<std::pair<uint32_t, uint64_t>> items;  // (stamp, bytes)
    items.reserve(stamps.size());
    for (uint32_t s : stamps) items.emplace_back(s, BoundTree::kBlockBytes);
    std::vector<BoundTree*> idle;
    if (m_owner) {
        for (BoundTree* tree : m_trees) {
            const uint32_t used = tree->m_lastUse.load(std::memory_order_relaxed);
            if (tree->m_wholeRetired || used >= now || !tree->retirable.load() || !tree->Idle()) continue;
            idle.push_back(tree);
            items.emplace_back(used, tree->m_ownBytes.load(std::memory_order_relaxed));
        }
    }
    if (items.empty()) return;
    std::sort(items.begin(), items.end());
    uint64_t freed = 0;
    uint32_t threshold = items.back().first;
    for (const auto& [stamp, n] : items) {
        freed += n;
        if (freed >= excess) {
            threshold = stamp;
            break;
        }
    }
    for (BoundTree* tree : m_trees) {
        const bool wasRetiring = !tree->m_retired.empty();
        tree->EvictExpandedBefore(threshold);
        if (!wasRetiring && !tree->m_retired.empty()) m_retiring.push_back(tree);
    }
    for (BoundTree* tree : idle) {
        if (tree->m_lastUse.load(std::memory_order_relaxed) > threshold) continue;
        if (tree->m_root.children.load(std::memory_order_acquire)) continue;  // expanded since it was entered
        tree->m_wholeRetired = true;
        tree->m_retiredOwnBytes = tree->m_ownBytes.load();
        m_retiredBytes.fetch_add(tree->m_retiredOwnBytes, std::memory_order_relaxed);
        m_treesRetired.fetch_add(1, std::memory_order_relaxed);
        m_owner->Retire(tree);
    }
}

BoundTree::BoundTree(const BaseSurface& surface, const vm::Program& boundProgram, const glm::dvec3& eye, BoundMode mode,
                     int maxDepth, CacheBudget* budget)
    : m_surface(surface), m_program(&boundProgram), m_eye(eye), m_mode(mode), m_maxDepth(maxDepth) {
    m_costlyBounds = boundProgram.code.size() >= 64;
    for (const vm::Instr& in : boundProgram.code) {
        const vm::Operation f = vm::OperationOf(in.op);
        if (f == vm::Operation::Noise || f == vm::Operation::PNoise || f == vm::Operation::CellNoise ||
            f == vm::Operation::Texture)
            m_costlyBounds = true;
    }
    if (!budget) m_ownBudget = std::make_unique<CacheBudget>(kDefaultCacheBytes);
    m_budget = budget ? budget : m_ownBudget.get();
    m_root.bound = MakeEvaluator()->Bound(0, 1, 0, 1);
    m_root.state.store(BoundNode::kReady);
    m_lastUse.store(m_budget->m_clock.load(std::memory_order_relaxed), std::memory_order_relaxed);
    {
        std::lock_guard<std::mutex> lock(m_budget->m_mutex);
        m_budgetIndex = m_budget->m_trees.size();
        m_budget->m_trees.push_back(this);
    }
    m_budget->Add(kBytes);
    if (m_budget->bytes.load(std::memory_order_relaxed) > m_budget->limit) m_budget->Enforce();
}

BoundTree::~BoundTree() {
    std::lock_guard<std::mutex> lock(m_budget->m_mutex);
    std::vector<BoundTree*>& trees = m_budget->m_trees;
    trees[m_budgetIndex] = trees.back();
    trees[m_budgetIndex]->m_budgetIndex = m_budgetIndex;
    trees.pop_back();
    if (!m_retired.empty()) std::erase(m_budget->m_retiring, this);
    uint64_t freed = 0, retired = 0;
    if (BoundNode* kids = m_root.children.load()) freed += FreeSubtree(kids);
    for (const Retired& r : m_retired) {
        freed += FreeSubtree(r.block);
        retired += r.bytes;
    }
    if (m_wholeRetired) retired += m_retiredOwnBytes;
    m_budget->m_retiredBytes.fetch_sub(retired, std::memory_order_relaxed);
    m_budget->Sub(freed / kBlockNodes * kBlockBytes + m_ownBytes.load());
    for (Slot* s = m_slots.load(); s;) {
        Slot* next = s->next;
        delete s;
        s = next;
    }
}

std::unique_ptr<RegionEvaluator> BoundTree::MakeEvaluator(const std::shared_ptr<EvaluatorPool>& pool) const {
    // A program with parameters keeps an interpreter of its own (SetProgram carries parameter
    // values over, so the pool's interpreter may only run programs without them, as every
    // specialised program is).
    const bool share = pool && m_program->params.empty();
    auto make = [&](auto type) -> std::unique_ptr<RegionEvaluator> {
        using N = decltype(type);
        return std::make_unique<RegionEvaluatorT<N>>(m_surface, *m_program, m_eye, share ? pool : nullptr);
    };
    const bool dual = m_program->usesDerivatives();
    if (m_mode == BoundMode::Affine) return dual ? make(vm::Dual<vm::Affine>()) : make(vm::Affine());
    if (m_mode == BoundMode::Reduced) return dual ? make(vm::Dual<vm::ReducedAffine>()) : make(vm::ReducedAffine());
    return dual ? make(vm::Dual<vm::Interval>()) : make(vm::Interval());
}

BoundTree::Slot* BoundTree::RegisterWalker() {
    for (Slot* s = m_slots.load(); s; s = s->next) {
        bool expected = false;
        if (s->used.compare_exchange_strong(expected, true)) return s;
    }
    Slot* s = new Slot;
    s->used.store(true);
    m_ownBytes.fetch_add(kWalkerBytes, std::memory_order_relaxed);
    m_budget->Add(kWalkerBytes);
    Slot* head = m_slots.load();
    do s->next = head;
    while (!m_slots.compare_exchange_weak(head, s));
    return s;
}

bool BoundTree::Publish(BoundNode& node, BoundNode* block) {
    BoundNode* expected = nullptr;
    return node.children.compare_exchange_strong(expected, block, std::memory_order_acq_rel, std::memory_order_acquire);
}

uint64_t BoundTree::FreeSubtree(BoundNode* block) {
    uint64_t nodes = kBlockNodes;
    for (int i = 0; i < kBlockNodes; ++i)
        if (BoundNode* kids = block[i].children.load(std::memory_order_relaxed)) nodes += FreeSubtree(kids);
    delete[] block;
    return nodes;
}

uint64_t BoundTree::CountSubtree(const BoundNode* block) {
    uint64_t nodes = kBlockNodes;
    for (int i = 0; i < kBlockNodes; ++i)
        if (const BoundNode* kids = block[i].children.load(std::memory_order_relaxed)) nodes += CountSubtree(kids);
    return nodes;
}

void BoundTree::Reclaim() {
    // The oldest epoch a walker still in a ray may have seen.
    uint64_t oldest = UINT64_MAX;
    for (Slot* s = m_slots.load(); s; s = s->next) {
        const uint64_t e = s->epoch.load();
        if (e != 0) oldest = std::min(oldest, e);
    }
    uint64_t freed = 0, retired = 0;
    std::erase_if(m_retired, [&](const Retired& r) {
        if (r.epoch >= oldest) return false;
        freed += FreeSubtree(r.block);
        retired += r.bytes;
        return true;
    });
    m_nodes.fetch_sub(freed, std::memory_order_relaxed);
    m_budget->m_retiredBytes.fetch_sub(retired, std::memory_order_relaxed);
    m_budget->Sub(freed / kBlockNodes * kBlockBytes);
}

void BoundTree::CollectStamps(std::vector<uint32_t>* stamps) {
    std::vector<BoundNode*> stack{&m_root};
    while (!stack.empty()) {
        BoundNode* n = stack.back();
        stack.pop_back();
        BoundNode* kids = n->children.load(std::memory_order_acquire);
        if (!kids) continue;
        stamps->push_back(n->stamp.load(std::memory_order_relaxed));
        for (int i = 0; i < kBlockNodes; ++i) stack.push_back(&kids[i]);
    }
}

void BoundTree::EvictExpandedBefore(uint32_t threshold) {
    const uint64_t epoch = m_epoch.load();
    uint64_t evicted = 0;
    std::vector<BoundNode*> stack{&m_root};
    while (!stack.empty()) {
        BoundNode* n = stack.back();
        stack.pop_back();
        std::atomic<BoundNode*>& children = n->children;
        BoundNode* kids = children.load(std::memory_order_acquire);
        if (!kids) continue;
        if (n->stamp.load(std::memory_order_relaxed) <= threshold) {
            // Unlink: rays that start from now on cannot reach the block; rays under way may
            // still hold it, so it is freed once they have all finished (Reclaim).
            kids = children.exchange(nullptr);
            if (kids) {
                const uint64_t bytes = CountSubtree(kids) / kBlockNodes * kBlockBytes;
                m_retired.push_back({kids, epoch, bytes});
                m_budget->m_retiredBytes.fetch_add(bytes, std::memory_order_relaxed);
                ++evicted;
            }
            continue;
        }
        for (int i = 0; i < kBlockNodes; ++i) stack.push_back(&kids[i]);
    }
    if (evicted == 0) return;
    m_evictions.fetch_add(evicted, std::memory_order_relaxed);
    m_passes.fetch_add(1, std::memory_order_relaxed);
    m_epoch.fetch_add(1);
    Reclaim();
}

bool BoundTree::Idle() const {
    for (Slot* s = m_slots.load(); s; s = s->next)
        if (s->used.load()) return false;
    return true;
}

BoundTreeStats BoundTree::stats() const {
    BoundTreeStats s;
    s.nodes = m_nodes.load();
    s.bytes = (s.nodes - 1) / kBlockNodes * kBlockBytes;
    s.blocksBuilt = m_blocksBuilt.load();
    s.evaluations = m_evaluations.load();
    s.privateCopies = m_private.load();
    s.lookups = m_lookups.load();
    s.evictions = m_evictions.load();
    s.evictionPasses = m_passes.load();
    s.buildSeconds = m_buildSeconds.load();
    s.trees = 1;
    return s;
}

void BoundTreeStats::Merge(const BoundTreeStats& o) {
    nodes += o.nodes;
    bytes += o.bytes;
    blocksBuilt += o.blocksBuilt;
    evaluations += o.evaluations;
    privateCopies += o.privateCopies;
    lookups += o.lookups;
    evictions += o.evictions;
    evictionPasses += o.evictionPasses;
    trees += o.trees;
    treesRetired += o.treesRetired;
    buildSeconds += o.buildSeconds;
}

BoundTree::Walker::Walker(BoundTree& tree) : m_tree(tree), m_slot(tree.RegisterWalker()) {}

BoundTree::Walker::~Walker() {
    m_slot->epoch.store(0);
    m_tree.m_lookups.fetch_add(m_lookups, std::memory_order_relaxed);
    m_tree.m_blocksBuilt.fetch_add(m_built, std::memory_order_relaxed);
    m_tree.m_evaluations.fetch_add(m_evaluations, std::memory_order_relaxed);
    m_tree.m_private.fetch_add(m_private, std::memory_order_relaxed);
    double seconds = m_tree.m_buildSeconds.load();
    while (!m_tree.m_buildSeconds.compare_exchange_weak(seconds, seconds + m_buildSeconds)) {}
    // Last: once no walker holds it, the tree's owner may free it (BoundForest).
    m_slot->used.store(false);
}

void BoundTree::Walker::Enter() {
    // Announce the epoch before reaching any node (sequentially consistent, against Evict's
    // unlink-then-advance).
    m_epoch = m_tree.m_epoch.load();
    m_slot->epoch.store(m_epoch);
    // The clock ticks every 64 rays a thread starts, in whichever trees: coarse, but enough to
    // tell old from recent.
    thread_local uint32_t raysSinceTick = 0;
    if (++raysSinceTick >= 64) {
        raysSinceTick = 0;
        m_tree.m_budget->m_clock.fetch_add(1, std::memory_order_relaxed);
    }
    m_clock = m_tree.m_budget->m_clock.load(std::memory_order_relaxed);
    if (m_tree.m_lastUse.load(std::memory_order_relaxed) < m_clock)
        m_tree.m_lastUse.store(m_clock, std::memory_order_relaxed);
    if (!m_privateBounds.empty()) m_privateBounds.clear();
}

void BoundTree::Walker::Leave() { m_slot->epoch.store(0, std::memory_order_release); }

BoundNode* BoundTree::Walker::Children(BoundNode& node) {
    if (node.stamp.load(std::memory_order_relaxed) < m_clock) node.stamp.store(m_clock, std::memory_order_relaxed);
    for (;;) {
        if (BoundNode* kids = node.children.load(std::memory_order_acquire)) return kids;
        BoundNode* block = new BoundNode[kBlockNodes];
        for (int i = 0; i < kBlockNodes; ++i) block[i].stamp.store(m_clock, std::memory_order_relaxed);
        if (!m_tree.Publish(node, block)) {
            // Another thread allocated them first (or they were evicted since: then try again).
            delete[] block;
            continue;
        }
        ++m_built;
        m_tree.m_nodes.fetch_add(kBlockNodes, std::memory_order_relaxed);
        m_tree.m_budget->Add(kBlockBytes);
        if (m_tree.m_budget->bytes.load(std::memory_order_relaxed) > m_tree.m_budget->limit) m_tree.m_budget->Enforce();
        return block;
    }
}

const RegionBound& BoundTree::Walker::Bound(BoundNode& child, double u0, double u1, double v0, double v1,
                                            RegionEvaluator& evaluator, uint64_t* evaluated) {
    ++m_lookups;
    uint8_t state = child.state.load(std::memory_order_acquire);
    if (state == BoundNode::kReady) return child.bound;
    const auto start = std::chrono::steady_clock::now();
    ++m_evaluations;
    ++*evaluated;
    const bool claimed = state == BoundNode::kEmpty &&
                         child.state.compare_exchange_strong(state, BoundNode::kClaimed, std::memory_order_acquire);
    RegionBound bound = evaluator.Bound(u0, u1, v0, v1);
    m_buildSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (claimed) {
        child.bound = bound;
        child.state.store(BoundNode::kReady, std::memory_order_release);
        return child.bound;
    }
    // Claimed by another thread that has not finished: use a private copy rather than wait.
    ++m_private;
    return m_privateBounds.emplace_back(bound);
}

static_assert(sizeof(BoundTree) <= BoundTree::kBytes, "BoundTree::kBytes counts the tree in its budget");

BoundForest::BoundForest(size_t count, CacheBudget& budget, Maker make)
    : m_budget(budget), m_make(std::move(make)), m_trees(count) {
    budget.SetOwner(this);
}

BoundForest::~BoundForest() {
    m_budget.SetOwner(nullptr);
    for (std::atomic<BoundTree*>& tree : m_trees) delete tree.load();
    for (const RetiredTree& r : m_incoming) delete r.tree;
    for (const RetiredTree& r : m_collecting) delete r.tree;
    for (ThreadSlot* s = m_threads.load(); s;) {
        ThreadSlot* next = s->next;
        delete s;
        s = next;
    }
}

BoundForest::ThreadSlot* BoundForest::RegisterThread() {
    ThreadSlot* s = new ThreadSlot;
    ThreadSlot* head = m_threads.load();
    do s->next = head;
    while (!m_threads.compare_exchange_weak(head, s));
    return s;
}

BoundTree& BoundForest::Tree(size_t i) {
    // Sequentially consistent, after the caller's announcement (With): a tree retired before this
    // read is not seen, one retired after it waits for the announcement to clear.
    BoundTree* tree = m_trees[i].load();
    if (tree) return *tree;
    std::unique_ptr<BoundTree> made = m_make(i, &m_budget);
    made->ownerIndex = i;
    // Another thread may have made it meanwhile: the first made is kept (both are the same).
    if (!m_trees[i].compare_exchange_strong(tree, made.get())) return *tree;
    m_made.fetch_add(1, std::memory_order_relaxed);
    made->retirable.store(true);
    return *made.release();
}

void BoundForest::Retire(BoundTree* tree) {
    // Unlink (an orphan, made again by another thread while a walker held it, is no longer linked),
    // then close the epoch: a thread announcing a later one cannot have read the tree.
    BoundTree* expected = tree;
    m_trees[tree->ownerIndex].compare_exchange_strong(expected, nullptr);
    const uint64_t epoch = m_epoch.fetch_add(1);
    std::lock_guard<std::mutex> lock(m_incomingMutex);
    m_incoming.push_back({tree, epoch});
    m_pending.fetch_add(1);
}

void BoundForest::Collect() {
    std::unique_lock<std::mutex> lock(m_collectMutex, std::try_to_lock);
    if (!lock.owns_lock()) return;
    {
        std::lock_guard<std::mutex> incoming(m_incomingMutex);
        m_collecting.insert(m_collecting.end(), m_incoming.begin(), m_incoming.end());
        m_incoming.clear();
    }
    uint64_t oldest = UINT64_MAX;  // the oldest epoch a thread looking a tree up announced
    for (ThreadSlot* s = m_threads.load(); s; s = s->next) {
        const uint64_t e = s->epoch.load();
        if (e != 0) oldest = std::min(oldest, e);
    }
    std::erase_if(m_collecting, [&](const RetiredTree& r) {
        // A walker made in the window holds the tree on: it goes once the walker does.
        if (r.epoch >= oldest || !r.tree->Idle()) return false;
        BoundTreeStats s = r.tree->stats();
        s.nodes = s.bytes = 0;  // held now: nothing, once freed
        m_freedStats.Merge(s);
        delete r.tree;
        m_pending.fetch_sub(1);
        return true;
    });
}

void BoundForest::Merge(BoundTreeStats* stats) {
    std::lock_guard<std::mutex> lock(m_collectMutex);
    std::lock_guard<std::mutex> incoming(m_incomingMutex);
    BoundTreeStats sum = m_freedStats;
    for (const std::atomic<BoundTree*>& tree : m_trees)
        if (const BoundTree* t = tree.load()) sum.Merge(t->stats());
    for (const std::vector<RetiredTree>* list : {&m_incoming, &m_collecting})
        for (const RetiredTree& r : *list) sum.Merge(r.tree->stats());
    sum.trees = m_made.load();  // the trees made, each retired one made again counted again
    stats->Merge(sum);
}

}  // namespace affray::renderer
