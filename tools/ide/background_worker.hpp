// The IDE server's heavy work (reading a project, compiling) on a thread of
// its own, so that the thread that serves every page never waits for one
// page's request: a page that opens a large project or compiles a long
// script delays its own replies only. Tasks run one after the other, in the
// order they came; each one's completion runs back on the server's
// io_context, where the state lives.

#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <asio/io_context.hpp>

namespace aseba::ide
{

class BackgroundWorker
{
  public:
    explicit BackgroundWorker(asio::io_context &io);
    // Waits for the task running, if any; the others are dropped.
    ~BackgroundWorker();
    BackgroundWorker(const BackgroundWorker &) = delete;
    BackgroundWorker &operator=(const BackgroundWorker &) = delete;

    // Runs `work` on the worker's thread, then `done` on the io_context's
    // with what `work` threw ("" when nothing). Whatever `work` produces,
    // it leaves where both share it (a shared_ptr they capture).
    void run(std::function<void()> work, std::function<void(const std::string &error)> done);

  private:
    void serve();

    asio::io_context &io_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::deque<std::function<void()>> tasks_;
    bool stopping_ = false;
    std::thread thread_;
};

} // namespace aseba::ide
