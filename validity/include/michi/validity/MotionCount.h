#ifndef MICHI_VALIDITY_MOTION_COUNT_
#define MICHI_VALIDITY_MOTION_COUNT_

namespace michi
{
    namespace validity
    {
        /** \brief One more motion in a counter of ompl::base::MotionValidator (valid_, invalid_).
            OMPL keeps those statistics in plain unsigned ints, and a planner that runs threads on one space
            (Thunder's ParallelPlan, ...) checks motions from several threads at once: ++valid_ was a data race
            (ThreadSanitizer, test_experience_thunder). A relaxed atomic add on the same member keeps OMPL's
            getters (getValidMotionCount(), Benchmark's valid segment fraction) working unchanged. */
        inline void countMotion(unsigned int &counter)
        {
            __atomic_fetch_add(&counter, 1u, __ATOMIC_RELAXED);
        }
    }  // namespace validity
}  // namespace michi

#endif
