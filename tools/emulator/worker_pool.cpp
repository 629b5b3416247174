// The arena's threads (see worker_pool.hpp).

#include "worker_pool.hpp"

#include <algorithm>

namespace aseba::arena
{
namespace
{

// A run lasts tens of microseconds to a millisecond, and the arena's runs
// come a simulated millisecond apart: a thread that waits for one spins
// this many times (some tens of microseconds) before it sleeps, so that a
// run rarely pays a wake-up, yet a busy computer loses little to the
// spinning (200 spins: 1,000 robots 2.0x real time, 4,000: 2.1x).
constexpr int spins_before_sleeping = 4000;
// Pieces per thread: one, so that each thread takes the same robots run
// after run and finds them in its core's cache (8 pieces a thread, handed
// out in turn, moved the robots between the cores: 100 robots 17x real
// time on two threads, 1,000 1.4-1.9x; one piece: 21x and 2.1x). A thread
// late to a run (the computer gave its core to something else) still
// leaves its piece to the others if none has taken it yet.
constexpr size_t pieces_per_thread = 1;
// The claim word: the run's piece count above, the next piece below.
constexpr unsigned piece_bits = 32;
constexpr uint64_t piece_mask = (uint64_t(1) << piece_bits) - 1;

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
        workers_.emplace_back([this] { serve(); });
}

WorkerPool::~WorkerPool()
{
    stopping_.store(true, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    generation_.notify_all();
    for (std::thread &worker : workers_)
        worker.join();
}

void WorkerPool::take_pieces()
{
    uint64_t claim = claim_.load(std::memory_order_acquire);
    for (;;) {
        uint32_t piece = uint32_t(claim & piece_mask);
        if (piece >= uint32_t(claim >> piece_bits))
            return; // every piece of the run taken
        // Taking piece `piece` of the run published in `claim`, whose fields
        // stay until that piece is done.
        if (!claim_.compare_exchange_weak(
              claim, claim + 1, std::memory_order_acq_rel, std::memory_order_acquire))
            continue;
        size_t begin = std::min(count_, size_t(piece) * piece_size_);
        size_t end = std::min(count_, begin + piece_size_);
        if (begin < end)
            (*work_)(begin, end);
        if (pieces_done_.fetch_add(1, std::memory_order_acq_rel) + 1 == pieces_)
            pieces_done_.notify_one();
        claim = claim_.load(std::memory_order_acquire);
    }
}

void WorkerPool::serve()
{
    uint32_t seen = 0;
    for (;;) {
        wait_until(generation_, [seen](uint32_t generation) { return generation != seen; });
        seen = generation_.load(std::memory_order_acquire);
        if (stopping_.load(std::memory_order_acquire))
            return;
        take_pieces();
    }
}

void WorkerPool::run(size_t count, const std::function<void(size_t begin, size_t end)> &work)
{
    if (workers_.empty()) {
        if (count > 0)
            work(0, count);
        return;
    }
    size_t wanted = threads() * pieces_per_thread;
    piece_size_ = std::max<size_t>(1, (count + wanted - 1) / wanted);
    pieces_ = uint32_t((count + piece_size_ - 1) / piece_size_);
    if (pieces_ == 0)
        return;
    work_ = &work;
    count_ = count;
    pieces_done_.store(0, std::memory_order_relaxed);
    // Published: a thread that takes a piece sees the fields above.
    claim_.store(uint64_t(pieces_) << piece_bits, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_acq_rel);
    generation_.notify_all();
    take_pieces();
    const uint32_t pieces = pieces_;
    wait_until(pieces_done_, [pieces](uint32_t done) { return done == pieces; });
}

} // namespace aseba::arena
