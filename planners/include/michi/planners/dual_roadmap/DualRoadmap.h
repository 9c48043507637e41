#ifndef MICHI_PLANNERS_DUAL_ROADMAP_
#define MICHI_PLANNERS_DUAL_ROADMAP_

#include <ompl/base/Planner.h>
#include <ompl/datastructures/NearestNeighbors.h>
#include <ompl/util/RandomNumbers.h>

#include <boost/graph/adjacency_list.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace planners
    {
        /**
           @anchor michiDualRoadmap
           @par Short description
           A PRM-like planner with two roadmaps, made for replanning while the world changes. The
           <em>learning roadmap</em> keeps every local path (edge) that was ever found collision-free, across
           queries and scene changes (and across runs: saveLearningRoadmap() / loadLearningRoadmap()). The
           <em>working roadmap</em> belongs to the current scene. When the scene changes, the working roadmap is
           cleared and seeded with randomly chosen learning-roadmap edges that are still valid (both states
           re-checked at once, the motion lazily or at once: lazy_seeding); then start and goal are connected and the
           roadmap is expanded by uniform samples, with edges checked lazily (only those on a candidate shortest path,
           as LazyPRM does). Edges that the search proved valid are added to the learning roadmap. The path found is
           smoothed (redundant vertices removed, shortcuts).

           How the planner learns that the scene changed (it only has \e si): either the owner calls
           notifySceneChanged(), or it installs a change counter with setSceneChangeCounter() (for michi's
           validity::Scene: `[scene] { return scene->changeCount(); }`) which solve() compares with the value it
           saw last. Without either, every solve() is treated as a new scene (always safe: nothing checked in an
           earlier solve() is trusted).

           clear() forgets the working roadmap and the query, not the learning roadmap (the experience, as OMPL's
           experience planners keep their database); clearLearningRoadmap() forgets it. Works in any state space
           that supports copyToReals / copyFromReals (for the file) and a uniform sampler.

           @par External documentation
           E. Yoshida, F. Kanehiro, K. Yokoi, P. Gergondet, "Online replanning for reactive robot motion: practical
           aspects", IROS 2010, pp. 5927-5933, DOI 10.1109/IROS.2010.5649645; E. Yoshida, F. Kanehiro, "Reactive
           robot motion using path replanning and deformation", ICRA 2011, pp. 5457-5462,
           DOI 10.1109/ICRA.2011.5980361. See docs/dual-roadmap.md.
        */
        class DualRoadmap : public ompl::base::Planner
        {
        public:
            explicit DualRoadmap(const ompl::base::SpaceInformationPtr &si);
            ~DualRoadmap() override;

            ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition &ptc) override;
            /** \brief Forget the working roadmap and the query (the learning roadmap stays). */
            void clear() override;
            void setup() override;
            /** \brief Working roadmap vertices (tag 0) and edges, then the learning roadmap's vertices (tag 1) and
                edges. */
            void getPlannerData(ompl::base::PlannerData &data) const override;

            /** \brief The scene changed: the next solve() rebuilds the working roadmap. Thread-safe. */
            void notifySceneChanged();
            /** \brief A function returning a number that changes whenever the scene changes; solve() compares it
                with the value of its previous solve(). An empty function: every solve() is a new scene. */
            void setSceneChangeCounter(std::function<std::uint64_t()> counter);

            /** \brief Forget the learning roadmap. */
            void clearLearningRoadmap();
            /** \brief Write the learning roadmap to a text file (states as reals); throws std::runtime_error
                naming the file. */
            void saveLearningRoadmap(const std::string &file) const;
            /** \brief Replace the learning roadmap by the one in \e file; throws std::runtime_error naming the file
                and what is wrong (other space, dimension, malformed). */
            void loadLearningRoadmap(const std::string &file);

            std::size_t learningVertexCount() const
            {
                return learnStates_.size();
            }
            std::size_t learningEdgeCount() const
            {
                return learnEdges_.size();
            }
            std::size_t workingVertexCount() const;
            std::size_t workingEdgeCount() const;
            /** \brief Learning edges put into the working roadmap at the last scene change. */
            std::size_t seededEdgeCount() const
            {
                return seeded_;
            }

            /** \brief Use the learning roadmap (seed from it, add to it); false is the ablation: a plain lazy
                roadmap rebuilt at every scene change. */
            void setUseLearning(bool use)
            {
                useLearning_ = use;
            }
            bool getUseLearning() const
            {
                return useLearning_;
            }
            /** \brief Learning edges tried when the working roadmap is seeded (chosen at random). */
            void setSeedEdges(unsigned int n)
            {
                seedEdges_ = n;
            }
            unsigned int getSeedEdges() const
            {
                return seedEdges_;
            }
            /** \brief Neighbours each new vertex is connected to (lazily). */
            void setMaxNearestNeighbors(unsigned int k)
            {
                k_ = k;
            }
            unsigned int getMaxNearestNeighbors() const
            {
                return k_;
            }
            /** \brief Longest edge, as a fraction of the space's maximum extent. */
            void setRangeFraction(double f)
            {
                rangeFraction_ = f;
            }
            double getRangeFraction() const
            {
                return rangeFraction_;
            }
            /** \brief Uniform samples added per expansion round. */
            void setBatchSize(unsigned int n)
            {
                batchSize_ = n;
            }
            unsigned int getBatchSize() const
            {
                return batchSize_;
            }
            /** \brief Smooth found paths (remove redundant vertices, shortcut). */
            void setSmooth(bool smooth)
            {
                smooth_ = smooth;
            }
            bool getSmooth() const
            {
                return smooth_;
            }
            /** \brief Seed the working roadmap with learning edges whose two states are valid in the new scene, and
                check their motions lazily (only on a candidate path, like the new edges); false: check every seeded
                motion at once, so the working roadmap holds only local paths proved valid. */
            void setLazySeeding(bool lazy)
            {
                lazySeeding_ = lazy;
            }
            bool getLazySeeding() const
            {
                return lazySeeding_;
            }
            /** \brief The learning roadmap stops growing at this many edges. */
            void setMaxLearningEdges(unsigned int n)
            {
                maxLearningEdges_ = n;
            }
            unsigned int getMaxLearningEdges() const
            {
                return maxLearningEdges_;
            }

        private:
            struct VertexProperties
            {
                ompl::base::State *state{nullptr};
                long learnId{-1};  ///< index in the learning roadmap, -1 when not (yet) there
            };
            struct EdgeProperties
            {
                double weight{0.};
                bool checked{false};  ///< proved valid in the current scene
            };
            using Graph =
                boost::adjacency_list<boost::setS, boost::vecS, boost::undirectedS, VertexProperties, EdgeProperties>;
            using Vertex = Graph::vertex_descriptor;

            void freeWorking();
            void rebuildWorking(const ompl::base::PlannerTerminationCondition &ptc);
            Vertex addWorkingVertex(ompl::base::State *state, long learnId);
            void connectLazily(Vertex v);
            bool sceneChanged();
            /** \brief A* from start to any goal vertex; empty when none is reachable. */
            std::vector<Vertex> shortestPath(Vertex start, const std::vector<Vertex> &goals) const;
            /** \brief Check the unchecked edges of \e path; removes the first invalid one. */
            bool validatePath(const std::vector<Vertex> &path, const ompl::base::PlannerTerminationCondition &ptc);
            long learnVertex(Vertex v);
            void learnEdge(Vertex a, Vertex b);

            Graph graph_;
            std::shared_ptr<ompl::NearestNeighbors<Vertex>> nn_;
            std::vector<Vertex> startVertices_;
            std::vector<Vertex> goalVertices_;
            ompl::base::StateSamplerPtr sampler_;
            ompl::RNG rng_;

            std::vector<ompl::base::State *> learnStates_;
            std::vector<std::pair<std::size_t, std::size_t>> learnEdges_;
            std::set<std::pair<std::size_t, std::size_t>> learnEdgeSet_;

            std::function<std::uint64_t()> counter_;
            std::uint64_t lastCount_{0};
            bool haveCount_{false};
            std::atomic<bool> changed_{true};
            std::size_t seeded_{0};
            std::atomic<std::size_t> learningEdgeCountAtomic_{0};  ///< for the progress property (other thread)

            bool useLearning_{true};
            unsigned int seedEdges_{50};
            unsigned int k_{10};
            double rangeFraction_{0.3};
            unsigned int batchSize_{20};
            bool smooth_{true};
            bool lazySeeding_{true};
            unsigned int maxLearningEdges_{50000};
        };
    }  // namespace planners
}  // namespace michi

#endif
