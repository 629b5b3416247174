// The arena's threads (see worker_pool.hpp).

#include "worker_pool.hpp"

namespace aseba::arena
{
namespace
{

// A run lasts tens of microseconds: a thread that waits for one spins this
// many times before it sleeps, so that a run rarely pays a wake-up.
constexpr int spins_before_sleeping = 200;

template<typename Ready>
void wait_until(const std::atomic<uint32_t> &value, Ready ready)
{
    for (int spin = 0; spin < spins_before_sleeping; spin++) {
        if (ready(value.load(std::memory_order_acquire)))
            return;
#if defined(__x86_64__) || defined(__i386__)
        __builtin_ia32_pause();
#endif
    }
    for (uint32_t seen = value.load(std::memory_order_acquire); !ready(seen);
         seen = value.load(std::memory_order_acquire))
        value.wait(seen, std::memory_order_acquire);
}

} // namespace

WorkerPool::WorkerPool(unsigned threads)
{
    for (unsigned number = 1; number < threads; number++)
        workers_.emplace_back([this, number] { serve(number); });
}

WorkerPool::~WorkerPool()
{
    stopping_.store(true, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    generation_.notify_all();
    for (std::thread &worker : workers_)
        worker.join();
}

void WorkerPool::share(unsigned number, unsigned shares)
{
    size_t begin = count_ * number / shares;
    size_t end = count_ * (number + 1) / shares;
    if (begin < end)
        (*work_)(begin, end);
}

void WorkerPool::serve(unsigned number)
{
    uint32_t done = 0;
    for (;;) {
        wait_until(generation_, [done](uint32_t generation) { return generation != done; });
        done = generation_.load(std::memory_order_acquire);
        if (stopping_.load(std::memory_order_acquire))
            return;
        share(number, threads());
        if (running_.fetch_sub(1, std::memory_order_acq_rel) == 1)
            running_.notify_one();
    }
}

void WorkerPool::run(size_t count, const std::function<void(size_t begin, size_t end)> &work)
{
    if (workers_.empty()) {
        if (count > 0)
            work(0, count);
        return;
    }
    work_ = &work;
    count_ = count;
    running_.store(uint32_t(workers_.size()), std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    generation_.notify_all();
    share(0, threads());
    wait_until(running_, [](uint32_t running) { return running == 0; });
}

} // namespace aseba::arena
