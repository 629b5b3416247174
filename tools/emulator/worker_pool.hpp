// A fixed set of threads that share out a loop over items, the calling
// thread among them: the arena runs its robots' firmware on every core this
// way, a millisecond at a time. The items are cut into pieces that each
// thread takes in turn, so that a thread the computer does not run for a
// while holds the others up by one piece at most. Each call returns when
// every piece is done, so what the items write is all visible after it.

#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

namespace aseba::arena
{

class WorkerPool
{
  public:
    // `threads` in all, the caller's included (1: no other thread).
    explicit WorkerPool(unsigned threads);
    ~WorkerPool();
    WorkerPool(const WorkerPool &) = delete;
    WorkerPool &operator=(const WorkerPool &) = delete;

    unsigned threads() const
    {
        return unsigned(workers_.size()) + 1;
    }

    // Calls work(begin, end) on contiguous pieces covering items 0..count,
    // on any of the threads, and returns once all are done.
    void run(size_t count, const std::function<void(size_t begin, size_t end)> &work);

  private:
    void serve();
    // Does pieces of the run until none is left.
    void take_pieces();

    std::vector<std::thread> workers_;
    // Bumped for each run: the workers wait on it.
    std::atomic<uint32_t> generation_{ 0 };
    std::atomic<bool> stopping_{ false };
    // The run, its pieces and those done. A thread takes a piece by bumping
    // the claim word (the run's piece count, then the next piece), so that
    // one late from a finished run finds no piece to take.
    const std::function<void(size_t, size_t)> *work_ = nullptr;
    size_t count_ = 0;
    size_t piece_size_ = 1;
    uint32_t pieces_ = 0;
    std::atomic<uint64_t> claim_{ 0 };
    std::atomic<uint32_t> pieces_done_{ 0 };
};

} // namespace aseba::arena
