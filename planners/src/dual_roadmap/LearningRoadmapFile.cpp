// DualRoadmap's learning roadmap on disk (saveLearningRoadmap(), loadLearningRoadmap()): a text file of the
// learning states' reals and the edges between them; the file format is in docs/dual-roadmap.md.
#include <michi/planners/dual_roadmap/DualRoadmap.h>
#include <michi/validity/InputFile.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace ob = ompl::base;

namespace michi
{
    namespace planners
    {
        namespace
        {
            // First word of a saved learning roadmap, followed by the format version (docs/dual-roadmap.md,
            // "DualRoadmap").
            const char *FILE_MAGIC = "michi-dual-roadmap";
        }  // namespace

        void DualRoadmap::saveLearningRoadmap(const std::string &file) const
        {
            const auto &space = si_->getStateSpace();
            std::ostringstream out;
            // 17 significant digits: every double reads back exactly, so a loaded roadmap has the same states as the
            // saved one.
            out.precision(17);
            out << FILE_MAGIC << " 1\n";
            std::vector<double> reals;
            {
                ob::State *probe = si_->allocState();  // the number of reals in a state
                space->copyToReals(reals, probe);
                si_->freeState(probe);
            }
            out << "space " << space->getDimension() << " " << reals.size() << " " << space->getName() << "\n";
            out << "vertices " << learnStates_.size() << "\n";
            for (const auto *s : learnStates_)
            {
                space->copyToReals(reals, s);
                for (std::size_t i = 0; i < reals.size(); ++i)
                    out << (i ? " " : "") << reals[i];
                out << "\n";
            }
            out << "edges " << learnEdges_.size() << "\n";
            for (const auto &e : learnEdges_)
                out << e.first << " " << e.second << "\n";
            // Written to a sibling file and renamed: a failed or interrupted write never leaves a truncated roadmap
            // under the file's name.
            const std::string tmp = file + ".tmp";
            {
                std::ofstream f(tmp);
                if (!f || !(f << out.str()) || !f.flush())
                    throw std::runtime_error(file + ": cannot write the learning roadmap");
            }
            if (std::rename(tmp.c_str(), file.c_str()) != 0)
            {
                std::remove(tmp.c_str());
                throw std::runtime_error(file + ": cannot write the learning roadmap");
            }
        }

        void DualRoadmap::loadLearningRoadmap(const std::string &file)
        {
            validity::requireInputFile(file);
            std::ifstream in(file);
            if (!in)
                throw std::runtime_error(file + ": cannot read the learning roadmap");
            auto fail = [&](const std::string &what)
            {
                throw std::runtime_error(file + ": " + what);
            };
            const auto &space = si_->getStateSpace();
            std::string magic, word, name;
            int version = 0;
            unsigned int dimension = 0;
            std::size_t realCount = 0;
            if (!(in >> magic >> version) || magic != FILE_MAGIC || version != 1)
                fail("not a DualRoadmap learning roadmap (expected '" + std::string(FILE_MAGIC) + " 1')");
            if (!(in >> word >> dimension >> realCount >> name) || word != "space")
                fail("expected 'space DIMENSION REALS NAME'");
            std::vector<double> reals;
            {
                ob::State *probe = si_->allocState();  // the number of reals in a state
                space->copyToReals(reals, probe);
                si_->freeState(probe);
            }
            // The space's name is written for people but not compared: the same robot may be set up under another name.
            // Dimension and number of reals are what copyFromReals() depends on.
            if (dimension != space->getDimension() || realCount != reals.size())
                fail("made for a space of dimension " + std::to_string(dimension) + " (" + std::to_string(realCount) +
                     " reals), this one has dimension " + std::to_string(space->getDimension()) + " (" +
                     std::to_string(reals.size()) + " reals)");
            std::size_t nv = 0, ne = 0;
            if (!(in >> word >> nv) || word != "vertices")
                fail("expected 'vertices N'");
            const std::size_t nr = reals.size();
            std::vector<ob::State *> states;
            auto freeAll = [&]
            {
                for (auto *s : states)
                    si_->freeState(s);
            };
            for (std::size_t i = 0; i < nv; ++i)
            {
                for (std::size_t j = 0; j < nr; ++j)
                    if (!(in >> reals[j]))
                    {
                        freeAll();
                        fail("vertex " + std::to_string(i) + ": expected " + std::to_string(nr) + " numbers");
                    }
                states.push_back(si_->allocState());
                space->copyFromReals(states.back(), reals);
            }
            std::vector<std::pair<std::size_t, std::size_t>> edges;
            if (!(in >> word >> ne) || word != "edges")
            {
                freeAll();
                fail("expected 'edges N'");
            }
            for (std::size_t i = 0; i < ne; ++i)
            {
                std::size_t a = 0, b = 0;
                if (!(in >> a >> b) || a >= nv || b >= nv || a == b)
                {
                    freeAll();
                    fail("edge " + std::to_string(i) + ": expected two different vertex indices below " +
                         std::to_string(nv));
                }
                edges.emplace_back(std::min(a, b), std::max(a, b));
            }
            // Nothing is changed until the whole file has been read and checked: a bad file leaves the old learning
            // roadmap as it was.
            clearLearningRoadmap();
            learnStates_ = std::move(states);
            for (const auto &e : edges)
                if (learnEdgeSet_.insert(e).second)
                    learnEdges_.push_back(e);
            learningEdgeCountAtomic_ = learnEdges_.size();
            changed_ = true;  // the working roadmap holds ids of the old learning roadmap
        }
    }  // namespace planners
}  // namespace michi
