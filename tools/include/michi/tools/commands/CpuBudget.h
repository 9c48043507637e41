#ifndef MICHI_TOOLS_COMMANDS_CPU_BUDGET_
#define MICHI_TOOLS_COMMANDS_CPU_BUDGET_

#include <cstddef>
#include <functional>
#include <mutex>
#include <utility>

namespace michi
{
    namespace tools
    {
        /** \brief A budget of one thread's CPU time, asked at every step of a planner (michi replan's `clock: cpu`).
            Reading a thread's CPU clock is a system call (about 1.4 us on the development machine, against about
            30 ns for the wall clock), and a planner asks at every vertex and motion it checks: read on every ask,
            it was a quarter of a cheap DualRoadmap replan. A thread's CPU time grows no faster than the wall clock,
            so the CPU clock is read again only once the wall time since its last read could have used up the
            budget; the budget is noticed as soon as with a read on every ask. Thread-safe (PRM asks from two
            threads). Both clocks in seconds. */
        class CpuBudget
        {
        public:
            using Clock = std::function<double()>;

            CpuBudget(double seconds, Clock cpu, Clock wall) : cpu_(std::move(cpu)), wall_(std::move(wall))
            {
                // wall first, then CPU: the CPU time at any later wall time w is at most cpuAt_ + (w - wallAt_)
                wallAt_ = wall_();
                cpuAt_ = cpu_();
                ++cpuReads_;
                end_ = cpuAt_ + seconds;
            }

            /** \brief Has the thread used up the budget? */
            bool spent()
            {
                std::lock_guard<std::mutex> lock(mutex_);
                const double wall = wall_();
                if (cpuAt_ + (wall - wallAt_) <= end_)
                    return false;
                wallAt_ = wall;
                cpuAt_ = cpu_();
                ++cpuReads_;
                return cpuAt_ > end_;
            }

            /** \brief How often the CPU clock was read (the constructor's read included). */
            std::size_t cpuReads() const
            {
                std::lock_guard<std::mutex> lock(mutex_);
                return cpuReads_;
            }

        private:
            Clock cpu_, wall_;
            mutable std::mutex mutex_;
            double wallAt_{0.}, cpuAt_{0.}, end_{0.};
            std::size_t cpuReads_{0};
        };
    }  // namespace tools
}  // namespace michi

#endif
