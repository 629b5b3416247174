// A fixed set of threads that share out a loop over items, the calling
// thread taking the first share: the arena runs its robots' firmware on
// every core this way, a millisecond at a time. Each call returns when
// every share is done, so what the items write is all visible after it.

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

    // Calls work(begin, end) on contiguous shares of items 0..count, one
    // share per thread, and returns once all are done.
    void run(size_t count, const std::function<void(size_t begin, size_t end)> &work);

  private:
    void serve(unsigned share);
    void share(unsigned number, unsigned shares);

    std::vector<std::thread> workers_;
    // Bumped for each run (workers wait on it), and the shares still running.
    std::atomic<uint32_t> generation_{ 0 };
    std::atomic<uint32_t> running_{ 0 };
    std::atomic<bool> stopping_{ false };
    const std::function<void(size_t, size_t)> *work_ = nullptr;
    size_t count_ = 0;
};

} // namespace aseba::arena
