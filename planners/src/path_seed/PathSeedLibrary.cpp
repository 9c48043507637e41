#include <michi/planners/path_seed/PathSeedLibrary.h>
#include <michi/validity/InputFile.h>

#include <ompl/datastructures/NearestNeighborsLinear.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace michi
{
    namespace planners
    {
        PathSeedLibrary::PathSeedLibrary(SeedVariant variant) : variant_(variant)
        {
        }

        void PathSeedLibrary::add(const std::vector<Eigen::VectorXd> &path)
        {
            SeedRecord record;
            record.code = encodePath(path, variant_);
            record.start = path.front();
            record.goal = path.back();
            for (std::size_t i = 0; i + 1 < path.size(); ++i)
                record.length += (path[i + 1] - path[i]).norm();
            // Finite joint values can still give an infinite seed (values of ~1e155 or more overflow the length and
            // the deviations): save() would write it and load() refuse the whole file, so such a path is refused
            // here, naming what overflowed.
            const auto finite = [](const std::vector<double> &values)
            {
                return std::all_of(values.begin(), values.end(),
                                   [](double x)
                                   {
                                       return std::isfinite(x);
                                   });
            };
            const char *overflow = !std::isfinite(record.length)    ? "length"
                                   : !finite(record.code.ratio)     ? "ratio"
                                   : !finite(record.code.deviation) ? "deviation"
                                   : !finite(record.code.direction) ? "direction"
                                   : !finite(record.code.axis)      ? "axis"
                                                                    : nullptr;
            if (overflow != nullptr)
                throw std::invalid_argument(std::string("PathSeedLibrary: the path's seed is not finite (its ") +
                                            overflow + " overflows: joint values too large to encode); not added");
            // The library is shared: a benchmark thread reads its size while a solve() learns into it.
            std::lock_guard<std::mutex> lock(mutex_);
            if (dimension_ != 0 && record.code.dimension != dimension_)
                throw std::invalid_argument("PathSeedLibrary: a path of dimension " +
                                            std::to_string(record.code.dimension) + " in a library of dimension " +
                                            std::to_string(dimension_));
            dimension_ = record.code.dimension;
            record.id = nextId_++;
            seeds_.push_back(std::move(record));
            shrink();
        }

        void PathSeedLibrary::shrink()
        {
            while (capacity_ > 0 && seeds_.size() > capacity_)
            {
                // A seed that helped in no solution goes first; among equals the oldest, so a seed just learned still
                // gets its chance.
                // fewest uses, then oldest (smallest id)
                const auto worst = std::min_element(seeds_.begin(), seeds_.end(),
                                                    [](const SeedRecord &a, const SeedRecord &b)
                                                    {
                                                        return a.uses != b.uses ? a.uses < b.uses : a.id < b.id;
                                                    });
                seeds_.erase(worst);
            }
        }

        void PathSeedLibrary::setCapacity(std::size_t seeds)
        {
            std::lock_guard<std::mutex> lock(mutex_);
            capacity_ = seeds;
            shrink();
        }

        std::size_t PathSeedLibrary::capacity() const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            return capacity_;
        }

        void PathSeedLibrary::markUsed(std::uint64_t id)
        {
            std::lock_guard<std::mutex> lock(mutex_);
            // Seeds are named by id, not by index: shrink() erases entries and would shift the indices of the rest.
            for (auto &s : seeds_)
                if (s.id == id)
                    ++s.uses;
        }

        std::vector<SeedRecord> PathSeedLibrary::candidates(const Eigen::VectorXd &start, const Eigen::VectorXd &goal,
                                                            std::size_t k) const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            std::vector<SeedRecord> out;
            if (seeds_.empty() || k == 0 || start.size() != dimension_ || goal.size() != dimension_)
                return out;
            // OMPL's nearest-neighbour structure over seed indices; index seeds_.size() stands for the query
            const std::size_t query = seeds_.size();
            // Linear: the structure is rebuilt for every query (the library may have grown), and a linear one needs no
            // build step.
            ompl::NearestNeighborsLinear<std::size_t> nn;
            nn.setDistanceFunction(
                [&](const std::size_t a, const std::size_t b)
                {
                    const Eigen::VectorXd &sa = a == query ? start : seeds_[a].start;
                    const Eigen::VectorXd &ga = a == query ? goal : seeds_[a].goal;
                    const Eigen::VectorXd &sb = b == query ? start : seeds_[b].start;
                    const Eigen::VectorXd &gb = b == query ? goal : seeds_[b].goal;
                    // Query distance in the joint space of (start, goal) pairs: a seed recorded for a nearby start and
                    // goal decodes to a path close to its own, so it is the most likely to fit (paper 001 leaves the
                    // choice of seeds open).
                    return std::sqrt((sa - sb).squaredNorm() + (ga - gb).squaredNorm());
                });
            std::vector<std::size_t> all(seeds_.size());
            for (std::size_t i = 0; i < all.size(); ++i)
                all[i] = i;
            nn.add(all);
            std::vector<std::size_t> nearest;
            nn.nearestK(query, k, nearest);
            for (std::size_t i : nearest)
                out.push_back(seeds_[i]);
            return out;
        }

        std::size_t PathSeedLibrary::size() const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            return seeds_.size();
        }

        unsigned int PathSeedLibrary::dimension() const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            return dimension_;
        }

        SeedRecord PathSeedLibrary::seed(std::size_t i) const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            return seeds_.at(i);
        }

        void PathSeedLibrary::clear()
        {
            std::lock_guard<std::mutex> lock(mutex_);
            seeds_.clear();
            dimension_ = 0;
        }

        namespace
        {
            void writeValues(std::ostream &out, const char *name, const double *v, std::size_t n)
            {
                out << name << ' ' << n;
                for (std::size_t i = 0; i < n; ++i)
                    out << ' ' << v[i];
                out << '\n';
            }

            /** Reads the library file line by line; every failure names the file and the line. */
            class LineReader
            {
            public:
                LineReader(std::istream &in, std::string file) : in_(in), file_(std::move(file))
                {
                }

                [[noreturn]] void fail(const std::string &message) const
                {
                    throw PathSeedFileError(file_ + ": line " + std::to_string(line_) + ": " + message);
                }

                std::istringstream next(const std::string &expected)
                {
                    std::string text;
                    if (!std::getline(in_, text))
                    {
                        ++line_;
                        fail("unexpected end of file (expected " + expected + ")");
                    }
                    ++line_;
                    return std::istringstream(text);
                }

                /** A line "<name> <count> v1 ... v<count>"; \e count must equal \e expected when non-zero. */
                std::vector<double> values(const std::string &name, std::size_t expected, bool fixed)
                {
                    auto line = next(name);
                    std::string word;
                    std::size_t n = 0;
                    if (!(line >> word) || word != name || !(line >> n))
                        fail("expected '" + name + " <count> <values>'");
                    if (fixed && n != expected)
                        fail("'" + name + "' has " + std::to_string(n) + " values, expected " +
                             std::to_string(expected));
                    // A corrupt count must fail with the line, not with std::bad_alloc from the vector below.
                    if (n > 100000000)
                        fail("'" + name + "' count too large");
                    std::vector<double> v(n);
                    // A NaN or infinity would decode into states the checkers cannot judge: refuse them here,
                    // naming the line.
                    for (std::size_t i = 0; i < n; ++i)
                        if (!(line >> v[i]) || !std::isfinite(v[i]))
                            fail("'" + name + "': value " + std::to_string(i + 1) + " of " + std::to_string(n) +
                                 " missing or not a finite number");
                    if (line >> word)
                        fail("'" + name + "': more values than its count " + std::to_string(n));
                    return v;
                }

            private:
                std::istream &in_;
                std::string file_;
                int line_{0};
            };
        }  // namespace

        void PathSeedLibrary::save(const std::string &file) const
        {
            std::lock_guard<std::mutex> lock(mutex_);
            // Written to a sibling file and renamed over the old one: an interrupted save never leaves a truncated
            // library.
            const std::string tmp = file + ".tmp";
            {
                std::ofstream out(tmp);
                if (!out)
                    throw std::runtime_error(file + ": cannot write the path seed library");
                // 17 significant digits: every double reads back exactly, so a reloaded seed decodes to the same path.
                out << std::setprecision(17);
                out << FILE_MAGIC << ' ' << FILE_VERSION << '\n';
                out << "variant " << seedVariantName(variant_) << '\n';
                out << "dimension " << dimension_ << '\n';
                out << "seeds " << seeds_.size() << '\n';
                for (const auto &s : seeds_)
                {
                    out << "seed " << s.code.waypoints() << ' ' << s.length << '\n';
                    writeValues(out, "start", s.start.data(), s.start.size());
                    writeValues(out, "goal", s.goal.data(), s.goal.size());
                    writeValues(out, "axis", s.code.axis.data(), s.code.axis.size());
                    writeValues(out, "ratio", s.code.ratio.data(), s.code.ratio.size());
                    writeValues(out, "deviation", s.code.deviation.data(), s.code.deviation.size());
                    writeValues(out, "direction", s.code.direction.data(), s.code.direction.size());
                }
                out.close();
                if (!out)
                {
                    std::remove(tmp.c_str());
                    throw std::runtime_error(file + ": cannot write the path seed library");
                }
            }
            if (std::rename(tmp.c_str(), file.c_str()) != 0)
            {
                std::remove(tmp.c_str());
                throw std::runtime_error(file + ": cannot write the path seed library (rename failed)");
            }
        }

        std::shared_ptr<PathSeedLibrary> PathSeedLibrary::load(const std::string &file)
        {
            try
            {
                validity::requireInputFile(file);
            }
            catch (const validity::InputFileError &e)
            {
                throw PathSeedFileError(file + ": cannot open the path seed library: " + e.reason());
            }
            std::ifstream in(file);
            if (!in)
                throw PathSeedFileError(file + ": cannot open the path seed library");
            LineReader r(in, file);
            {
                auto line = r.next(FILE_MAGIC);
                std::string magic;
                int version = 0;
                if (!(line >> magic) || magic != FILE_MAGIC)
                    r.fail(std::string("not a path seed library (expected '") + FILE_MAGIC + " <version>')");
                if (!(line >> version) || version != FILE_VERSION)
                    r.fail("unsupported version (this michi reads version " + std::to_string(FILE_VERSION) + ")");
            }
            std::string word, variantName;
            auto line = r.next("variant");
            if (!(line >> word >> variantName) || word != "variant")
                r.fail("expected 'variant blocks|rotation'");
            SeedVariant variant;
            try
            {
                variant = seedVariantFromName(variantName);
            }
            catch (const std::invalid_argument &e)
            {
                r.fail(e.what());
            }
            auto lib = std::make_shared<PathSeedLibrary>(variant);
            unsigned int dimension = 0;
            line = r.next("dimension");
            if (!(line >> word >> dimension) || word != "dimension")
                r.fail("expected 'dimension <N>'");
            std::size_t count = 0;
            line = r.next("seeds");
            if (!(line >> word >> count) || word != "seeds")
                r.fail("expected 'seeds <count>'");
            if (count > 0 && dimension == 0)
                r.fail("seeds in a library of dimension 0");
            for (std::size_t i = 0; i < count; ++i)
            {
                SeedRecord s;
                s.code.variant = variant;
                s.code.dimension = dimension;
                std::size_t M = 0;
                line = r.next("seed");
                if (!(line >> word >> M >> s.length) || word != "seed" || M > 10000000)
                    r.fail("expected 'seed <waypoints> <length>' (seed " + std::to_string(i + 1) + " of " +
                           std::to_string(count) + ")");
                const auto start = r.values("start", dimension, true);
                const auto goal = r.values("goal", dimension, true);
                s.start = Eigen::Map<const Eigen::VectorXd>(start.data(), dimension);
                s.goal = Eigen::Map<const Eigen::VectorXd>(goal.data(), dimension);
                const std::size_t B = s.code.blocks();
                s.code.axis = r.values("axis", s.code.directionWidth(), true);
                // Per waypoint and block (paper 001: joints 1-3, 4-6, ... for N > 3): one ratio r and one deviation tau
                // each; the directions delta take directionWidth() values per waypoint.
                s.code.ratio = r.values("ratio", M * B, true);
                s.code.deviation = r.values("deviation", M * B, true);
                s.code.direction = r.values("direction", M * s.code.directionWidth(), true);
                // tau is a norm |w - l| (paper 001): a negative one can only come from a damaged file.
                for (double t : s.code.deviation)
                    if (t < 0.)
                        r.fail("'deviation' values must not be negative");
                // Ids in file order, and use counts start at 0 (they are not saved): a loaded library forgets its
                // oldest seeds first.
                s.id = lib->nextId_++;
                lib->seeds_.push_back(std::move(s));
            }
            // An empty library takes the dimension of the first path added, as a new one does.
            lib->dimension_ = count > 0 ? dimension : 0;
            std::string rest;
            // Trailing data means a count is wrong somewhere: a silent stop would drop seeds unnoticed.
            while (std::getline(in, rest))
                if (rest.find_first_not_of(" \t\r") != std::string::npos)
                    r.fail("data after the last seed");
            return lib;
        }
    }  // namespace planners
}  // namespace michi
