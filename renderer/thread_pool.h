// renderer/thread_pool.h: the one set of worker threads a Renderer (renderer/renderer.h) owns.
// Preparing a scene (its primitives' boxes, the BVH) and rendering it (tiles) run their jobs on
// it, so `--threads` holds for both and threads are started once per run, not once per job.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace affray::renderer {

class ThreadPool {
  public:
    /// A pool of `threads` threads counting the caller's (0: one per core; at least one). The
    /// other threads are started here and wait for jobs.
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// The threads a job can use, the caller's included.
    int size() const { return static_cast<int>(m_threads.size()) + 1; }

    /// Calls job(w) for w = 0 .. workers-1, each on its own thread (workers is clamped to
    /// [1, size()]; w = 0 is the calling thread), and returns when every call has returned. The
    /// first exception a call throws is thrown here, after the others have returned. A Run from
    /// inside a job (of this pool or another) runs its calls one after the other on the calling
    /// thread: jobs never wait for threads that wait for them.
    void Run(int workers, const std::function<void(int worker)>& job);

    /// Calls body(i, worker) for every i in [0, n), spread over the pool's threads in chunks of
    /// `grain` taken in order (a thread takes the next chunk when it is done with one).
    void ForEach(size_t n, const std::function<void(size_t i, int worker)>& body, size_t grain = 1);

  private:
    void WorkerLoop(int index);

    std::vector<std::thread> m_threads;
    std::mutex m_runMutex;  // held by the Run that owns the threads
    std::mutex m_mutex;
    std::condition_variable m_wake, m_done;
    const std::function<void(int)>* m_job = nullptr;
    int m_workers = 0;          // the current job's
    int m_pending = 0;          // the pool's threads still in the current job
    unsigned m_generation = 0;  // counts jobs, so that a thread takes each once
    bool m_quit = false;
    std::exception_ptr m_error;
};

/// The threads `requested` means: itself if positive, else one per core.
int ThreadsFor(int requested);

}  // namespace affray::renderer
