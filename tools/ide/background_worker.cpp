// The IDE server's background thread (see background_worker.hpp).

#include "background_worker.hpp"

#include <exception>

#include <asio/post.hpp>

namespace aseba::ide
{

BackgroundWorker::BackgroundWorker(asio::io_context &io)
  : io_(io)
  , thread_([this] { serve(); })
{
}

BackgroundWorker::~BackgroundWorker()
{
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
}

void BackgroundWorker::run(std::function<void()> work,
                           std::function<void(const std::string &error)> done)
{
    {
        std::lock_guard lock(mutex_);
        tasks_.push_back([this, work = std::move(work), done = std::move(done)] {
            std::string error;
            try {
                work();
            } catch (const std::exception &exception) {
                error = exception.what();
            }
            asio::post(io_, [done, error] { done(error); });
        });
    }
    changed_.notify_one();
}

void BackgroundWorker::serve()
{
    for (;;) {
        std::function<void()> task;
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
            if (stopping_)
                return;
            task = std::move(tasks_.front());
            tasks_.pop_front();
        }
        task();
    }
}

} // namespace aseba::ide
