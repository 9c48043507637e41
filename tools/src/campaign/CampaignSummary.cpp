// summary.md of a merged campaign: the figures Planner Arena would show first, per planner and per dataset.
#include <michi/tools/campaign/CampaignMerge.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

namespace michi
{
    namespace tools
    {
        namespace
        {
            double value(const UnitRecord &r, const std::string &key)
            {
                const auto it = r.properties.find(key);
                if (it == r.properties.end() || it->second.empty())
                    return std::nan("");
                try
                {
                    return std::stod(it->second);
                }
                catch (const std::exception &)
                {
                    return std::nan("");
                }
            }

            bool isSolved(const UnitRecord &r)
            {
                // A crashed or killed unit has solved = 0 too, but only a unit that finished can have solved anything.
                return r.outcome == "done" && value(r, "solved BOOLEAN") == 1.;
            }

            /** the q-quantile by nearest rank (a value that occurred), NaN for none */
            double quantile(std::vector<double> v, double q)
            {
                v.erase(std::remove_if(v.begin(), v.end(),
                                       [](double x)
                                       {
                                           return std::isnan(x);
                                       }),
                        v.end());
                if (v.empty())
                    return std::nan("");
                std::sort(v.begin(), v.end());
                // The median of an even count averages the middle two, as usual; other quantiles take the nearest rank,
                // a time that actually occurred.
                if (q == 0.5)
                    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
                const auto rank = static_cast<std::size_t>(std::ceil(q * v.size()));
                return v[std::min(v.size(), std::max<std::size_t>(rank, 1)) - 1];
            }

            std::string num(double v, int precision = 4)
            {
                if (std::isnan(v))
                    return "–";
                std::ostringstream s;
                s << std::setprecision(precision) << v;
                return s.str();
            }

            struct Figures
            {
                std::size_t runs{0}, solved{0}, failed{0};
                std::vector<double> times, lengths, clearances;
                std::map<std::string, std::size_t> causes;

                void add(const UnitRecord &r)
                {
                    ++runs;
                    // Every run's time, failed ones included (at the time they gave up): dropping them would make a
                    // planner that often hangs look fast.
                    times.push_back(value(r, "time REAL"));
                    if (r.outcome != "done")
                    {
                        ++failed;
                        ++causes[r.outcome + (r.outcome == "crash" ? " " + r.cause : "")];
                    }
                    if (isSolved(r))
                    {
                        ++solved;
                        // Length and clearance only of solved runs: an unsolved run has no path to measure.
                        lengths.push_back(value(r, "solution length REAL"));
                        clearances.push_back(value(r, "solution clearance REAL"));
                    }
                }
            };

            /** the planners in plan order */
            std::vector<std::string> plannerOrder(const std::vector<UnitRecord> &records)
            {
                // Plan order (the campaign file's planner order), not alphabetical: tables read in the order the
                // campaign lists them.
                std::vector<std::string> order;
                for (const auto &r : records)
                    if (std::find(order.begin(), order.end(), r.plannerName) == order.end())
                        order.push_back(r.plannerName);
                return order;
            }
        }  // namespace

        std::string campaignSummary(const std::vector<UnitRecord> &records, std::size_t planned)
        {
            std::ostringstream md;
            const std::string name = records.empty() ? std::string("campaign") : records.front().campaign;
            md << "# Campaign " << name << "\n\n";
            std::size_t failed = 0;
            for (const auto &r : records)
                failed += r.outcome != "done";
            md << records.size() << " of " << planned << " work units merged";
            if (records.size() < planned)
                md << " (" << planned - records.size() << " missing: not run yet)";
            md << "; " << failed << " failed (crash, timeout or error: counted as unsolved runs)";
            if (!records.empty())
                md << "; time limit " << records.front().timeLimit << " s per run; michi "
                   << records.front().michiVersion;
            md << ". Times over all runs (a failed run counts at the time it gave up), length and clearance over "
                  "solved runs (paths re-checked by FCL).\n\n";

            const auto order = plannerOrder(records);
            std::map<std::string, Figures> perPlanner;
            std::vector<std::string> datasets;
            std::map<std::string, std::map<std::string, Figures>> perDataset;
            for (const auto &r : records)
            {
                perPlanner[r.plannerName].add(r);
                if (std::find(datasets.begin(), datasets.end(), r.dataset) == datasets.end())
                    datasets.push_back(r.dataset);
                perDataset[r.dataset][r.plannerName].add(r);
            }
            md << "| planner | runs | solved | failed | median time (s) | p95 time (s) | median length | median "
                  "clearance |\n";
            md << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
            for (const auto &p : order)
            {
                const Figures &f = perPlanner[p];
                md << "| " << p << " | " << f.runs << " | " << f.solved << " (" << num(100. * f.solved / f.runs, 3)
                   << " %) | " << f.failed << " | " << num(quantile(f.times, 0.5)) << " | "
                   << num(quantile(f.times, 0.95)) << " | " << num(quantile(f.lengths, 0.5)) << " | "
                   << num(quantile(f.clearances, 0.5), 3) << " |\n";
            }
            md << "\n## Per dataset\n\n";
            md << "| dataset | planner | runs | solved | failed | median time (s) | p95 time (s) | median length |\n";
            md << "|---|---|---:|---:|---:|---:|---:|---:|\n";
            for (const auto &d : datasets)
                for (const auto &p : order)
                {
                    if (!perDataset[d].count(p))
                        continue;
                    const Figures &f = perDataset[d][p];
                    md << "| " << d << " | " << p << " | " << f.runs << " | " << f.solved << " | " << f.failed << " | "
                       << num(quantile(f.times, 0.5)) << " | " << num(quantile(f.times, 0.95)) << " | "
                       << num(quantile(f.lengths, 0.5)) << " |\n";
                }
            bool anyFailure = false;
            for (const auto &p : order)
                anyFailure = anyFailure || !perPlanner[p].causes.empty();
            if (anyFailure)
            {
                md << "\n## Failed units\n\n| planner | outcome | units |\n|---|---|---:|\n";
                for (const auto &p : order)
                    for (const auto &kv : perPlanner[p].causes)
                        md << "| " << p << " | " << kv.first << " | " << kv.second << " |\n";
            }
            return md.str();
        }
    }  // namespace tools
}  // namespace michi
