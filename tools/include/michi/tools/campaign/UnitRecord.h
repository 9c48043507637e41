#ifndef MICHI_TOOLS_CAMPAIGN_UNIT_RECORD_
#define MICHI_TOOLS_CAMPAIGN_UNIT_RECORD_

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace michi
{
    namespace tools
    {
        /** \brief What a work unit is and what became of it: the file `campaign run` keeps per finished unit
            (`DIR/units/<id>.run`) and `campaign merge` reads. A unit's own process writes it when the planner
            returned; the shard's process writes it when the unit's process crashed, hung or failed. */
        struct UnitRecord
        {
            std::size_t id{0};
            std::string campaign;
            std::string dataset;
            std::string problem;  ///< the problem's name (the log's experiment)
            std::string problemFile;
            std::size_t query{0};
            std::string queryLabel;
            std::string plannerName;  ///< as in logs and the database (unitPlannerName())
            std::string plannerLabel;
            std::string planner;  ///< registry name
            std::map<std::string, std::string> params;
            std::string checker;
            unsigned int run{0};
            std::uint32_t seed{1};
            double timeLimit{0.};
            double memoryLimit{0.};
            std::string michiVersion;  ///< "0.1.0 (git abc1234)"
            /** \brief "done" (the planner returned; solved or not), "crash" (the unit's process died of a signal),
                "timeout" (killed after its time limit plus the hang margin) or "error" (it exited with an error,
                e.g. a start in collision under that checker); "pending" in the spec a unit's process is given. */
            std::string outcome;
            std::string cause;      ///< "SIGSEGV (signal 11)", "killed after 31.5 s", an error message; or empty
            int signal{0};          ///< the signal a crashed unit died of
            double wallTime{0.};    ///< seconds the unit's process ran, as the shard saw it
            std::string setupInfo;  ///< the problem's setup as OMPL prints it (the log's multi-line block)
            /** \brief The planner's settings as OMPL's Benchmark logs them ("name = value" lines), when it ran. */
            std::vector<std::string> settings;
            /** \brief The run's properties as OMPL's Benchmark records them ("time REAL" -> "0.0123") plus michi's
                (checker, check counts, path). */
            std::map<std::string, std::string> properties;
            /** \brief The planner's progress properties as OMPL's Benchmark names them ("best cost REAL"), when it
                reported any (RRT*, BIT*, PRM); the log's and database's `progress` data. */
            std::vector<std::string> progressNames;
            /** \brief The run's progress samples in time order, each the values of progressNames in that order. */
            std::vector<std::vector<std::string>> progress;
        };

        /** \brief The record as text (one "key=value" per line; values on one line). */
        std::string formatUnitRecord(const UnitRecord &record);

        /** \brief Parse formatUnitRecord() output; std::runtime_error naming \e source for a malformed record. */
        UnitRecord parseUnitRecord(const std::string &text, const std::string &source);

        /** \brief Write \e record atomically to \e file (a reader never sees half a record). */
        void writeUnitRecord(const UnitRecord &record, const std::string &file);

        /** \brief Read a record file; std::runtime_error naming it when it cannot be read or parsed. */
        UnitRecord readUnitRecord(const std::string &file);
    }  // namespace tools
}  // namespace michi

#endif
