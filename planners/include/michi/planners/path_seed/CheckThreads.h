#ifndef MICHI_PLANNERS_PATH_SEED_CHECK_THREADS_
#define MICHI_PLANNERS_PATH_SEED_CHECK_THREADS_

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief Helper threads kept for a planner's life, for PathSeed's shared-out path checks
            (checkPathFailFast, stitchPaths). A query hands out work many times (once per candidate path and per
            stitching round), each a few hundred state checks; a thread started per hand-out cost more than it
            saved where a state check takes microseconds (the xArm6: docs/path-seed.md). A helper that has just
            finished keeps polling for the next hand-out for a short while (\e spinMicroseconds) before it sleeps, so
            the hand-outs of one query do not each wait for a sleeping thread to wake. */
        class CheckThreads
        {
        public:
            /** \param helpers threads besides the caller's own */
            explicit CheckThreads(unsigned int helpers, unsigned int spinMicroseconds = 200);
            ~CheckThreads();
            CheckThreads(const CheckThreads &) = delete;
            CheckThreads &operator=(const CheckThreads &) = delete;

            unsigned int helpers() const
            {
                return static_cast<unsigned int>(threads_.size());
            }
            /** \brief Run \e job(0) on the calling thread and \e job(1) .. \e job(count - 1) on helpers (count - 1
                at most helpers()), for work the jobs claim as they go (an atomic counter over a list), which the
                caller's job alone can finish: a helper that has not begun its job when \e job(0) returns skips this
                hand-out instead of being waited for (a sleeping helper takes tens of microseconds to wake, and a
                hand-out whose first check fails is over sooner: docs/path-seed.md). Returns when every job that
                began has returned; an exception one threw is thrown again here. Not reentrant. */
            void share(unsigned int count, const std::function<void(unsigned int)> &job);

        private:
            void loop(unsigned int index);

            std::vector<std::thread> threads_;
            std::mutex mutex_;
            std::condition_variable wake_, finished_;
            const std::function<void(unsigned int)> *job_{nullptr};
            unsigned int count_{0};                     ///< jobs of the current hand-out, the caller's included
            std::atomic<std::uint64_t> generation_{0};  ///< hand-outs so far (a helper runs each at most once)
            unsigned int running_{0};                   ///< helpers' jobs begun and not yet returned
            bool open_{false};                          ///< the caller's job still runs: helpers may join
            std::atomic<bool> stop_{false};
            std::exception_ptr error_;
            unsigned int spin_;
        };
    }  // namespace planners
}  // namespace michi

#endif
