// renderer/thread_pool.cpp: ThreadPool, a fixed set of threads that run one job at a time.
#include "renderer/thread_pool.h"

#include <algorithm>
#include <atomic>

namespace affray::renderer {

namespace {
// Set on a thread while it runs a job's call: a Run from there runs serially.
thread_local bool t_inJob = false;
}  // namespace

int ThreadsFor(int requested) {
    return requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

ThreadPool::ThreadPool(int threads) {
    const int n = ThreadsFor(threads);
    m_threads.reserve(static_cast<size_t>(n - 1));
    for (int i = 1; i < n; ++i) m_threads.emplace_back(&ThreadPool::WorkerLoop, this, i);
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_quit = true;
    }
    m_wake.notify_all();
    for (std::thread& t : m_threads) t.join();
}

void ThreadPool::WorkerLoop(int index) {
    unsigned seen = 0;
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        m_wake.wait(lock, [&] { return m_quit || m_generation != seen; });
        if (m_quit) return;
        seen = m_generation;
        if (index >= m_workers) continue;  // not needed for this job
        const std::function<void(int)>* job = m_job;
        lock.unlock();
        std::exception_ptr error;
        t_inJob = true;
        try {
            (*job)(index);
        } catch (...) {
            error = std::current_exception();
        }
        t_inJob = false;
        lock.lock();
        if (error && !m_error) m_error = error;
        if (--m_pending == 0) m_done.notify_all();
    }
}

void ThreadPool::Run(int workers, const std::function<void(int worker)>& job) {
    workers = std::clamp(workers, 1, size());
    if (workers == 1 || t_inJob) {
        const bool outer = !t_inJob;
        t_inJob = true;
        struct Reset {
            bool outer;
            ~Reset() {
                if (outer) t_inJob = false;
            }
        } reset{outer};
        for (int w = 0; w < workers; ++w) job(w);
        return;
    }
    // One job at a time: a second caller (another thread using the same pool) waits its turn.
    std::lock_guard<std::mutex> serial(m_runMutex);
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_job = &job;
        m_workers = workers;
        m_pending = workers - 1;
        m_error = nullptr;
        ++m_generation;
    }
    m_wake.notify_all();
    std::exception_ptr error;
    t_inJob = true;
    try {
        job(0);
    } catch (...) {
        error = std::current_exception();
    }
    t_inJob = false;
    std::unique_lock<std::mutex> lock(m_mutex);
    m_done.wait(lock, [&] { return m_pending == 0; });
    m_job = nullptr;
    if (!error) error = m_error;
    lock.unlock();
    if (error) std::rethrow_exception(error);
}

void ThreadPool::ForEach(size_t n, const std::function<void(size_t i, int worker)>& body, size_t grain) {
    if (n == 0) return;
    grain = std::max<size_t>(1, grain);
    const size_t chunks = (n + grain - 1) / grain;
    std::atomic<size_t> next{0};
    Run(static_cast<int>(std::min<size_t>(chunks, size_t(size()))), [&](int worker) {
        for (size_t c = next++; c < chunks; c = next++)
            for (size_t i = c * grain, end = std::min(n, i + grain); i < end; ++i) body(i, worker);
    });
}

}  // namespace affray::renderer
