#include <michi/planners/path_seed/CheckThreads.h>

#include <chrono>

namespace michi
{
    namespace planners
    {
        CheckThreads::CheckThreads(unsigned int helpers, unsigned int spinMicroseconds) : spin_(spinMicroseconds)
        {
            for (unsigned int i = 0; i < helpers; ++i)
                threads_.emplace_back(&CheckThreads::loop, this, i + 1);
        }

        CheckThreads::~CheckThreads()
        {
            {
                std::lock_guard<std::mutex> lock(mutex_);
                stop_ = true;
            }
            wake_.notify_all();
            for (auto &t : threads_)
                t.join();
        }

        void CheckThreads::share(unsigned int count, const std::function<void(unsigned int)> &job)
        {
            if (count > helpers() + 1)
                count = helpers() + 1;
            if (count <= 1)
            {
                job(0);
                return;
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                job_ = &job;
                count_ = count;
                // a helper counts itself in when it begins, while the caller's job still runs
                running_ = 0;
                open_ = true;
                error_ = nullptr;
                ++generation_;
            }
            wake_.notify_all();
            std::exception_ptr own;
            try
            {
                job(0);
            }
            catch (...)
            {
                own = std::current_exception();
            }
            std::unique_lock<std::mutex> lock(mutex_);
            // from here no helper begins; those that began are waited for, since the job refers to the caller's
            // stack: no helper may still run it when share() returns
            open_ = false;
            finished_.wait(lock,
                           [this]
                           {
                               return running_ == 0;
                           });
            job_ = nullptr;
            if (own)
                std::rethrow_exception(own);
            if (error_)
                std::rethrow_exception(error_);
        }

        void CheckThreads::loop(unsigned int index)
        {
            std::uint64_t seen = 0;
            std::unique_lock<std::mutex> lock(mutex_);
            while (true)
            {
                if (!stop_ && generation_ == seen && spin_ > 0)
                {
                    // poll a little before sleeping: a query's next hand-out usually follows within microseconds
                    lock.unlock();
                    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(spin_);
                    while (!stop_.load() && generation_.load() == seen && std::chrono::steady_clock::now() < until)
                        std::this_thread::yield();
                    lock.lock();
                }
                wake_.wait(lock,
                           [&]
                           {
                               return stop_ || generation_ != seen;
                           });
                if (stop_)
                    return;
                seen = generation_;
                if (index >= count_ || !open_)
                    continue;  // this hand-out needs fewer threads, or the caller has finished it
                ++running_;
                const auto *job = job_;
                lock.unlock();
                std::exception_ptr error;
                try
                {
                    (*job)(index);
                }
                catch (...)
                {
                    error = std::current_exception();
                }
                lock.lock();
                if (error && !error_)
                    error_ = error;
                if (--running_ == 0)
                    finished_.notify_one();
            }
        }
    }  // namespace planners
}  // namespace michi
