#ifndef MICHI_PLANNERS_DUAL_ARM_WORKSPACE_
#define MICHI_PLANNERS_DUAL_ARM_WORKSPACE_

#include <michi/planners/HandIk.h>
#include <michi/planners/dual_arm/Manipulability.h>
#include <michi/validity/robot/RobotModel.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace michi
{
    namespace planners
    {
        /** \brief One arm of a dual-arm robot and the hand orientation it keeps in its work space (the
            target's position is ignored; every query sets it). */
        struct ArmTask
        {
            std::string name;  ///< "large", "small"
            ArmChain arm;
            HandTarget hand;
        };

        /** \brief Settings of the work-space analysis of paper 004 (Takahama, Nagatani & Tanaka). */
        struct DualArmSettings
        {
            double resolution{0.02};  ///< edge of a grid cell (metres); cells are tested at their centres
            double threshold{0.004};  ///< manipulability area: the small arm's w above this
            /// the paper's w = |det J| of the 6 x 6 Jacobian (docs/dual-arm.md: the position rows select no area at
            /// the paper's threshold)
            ManipulabilityRows rows{ManipulabilityRows::FULL};
            double stirSide{0.03};           ///< side of the stirring square (metres)
            double stirStep{0.0025};         ///< hand displacement between states of the stirring motion (metres)
            unsigned int seedSamples{3000};  ///< joint-space samples per arm whose hand positions seed the IK
            unsigned int seedsPerCell{4};    ///< nearest samples tried per cell (after the neighbours' solutions)
            unsigned int seed{1};            ///< ompl::RNG seed for the samples
            HandIkSettings ik;
        };

        /** \brief The stirring motion of the small arm: its hand draws a horizontal square about a centre,
            hand pointing down, the large arm holding still. States are full configurations. */
        struct StirringMotion
        {
            bool valid{false};
            std::string failure;  ///< why not, when not valid
            std::vector<std::vector<double>> states;
            std::vector<Eigen::Vector3d> hand;  ///< the small hand's target at each state
            std::vector<double> manipulability;
            double minManipulability{0.};
            std::vector<double> jointMotion;  ///< total |change| of each small-arm joint (radians)
        };

        /** \brief The regular grid the work spaces are sampled on. */
        struct WorkspaceGrid
        {
            Eigen::Vector3d origin{Eigen::Vector3d::Zero()};  ///< corner of cell (0, 0, 0)
            std::array<int, 3> size{{0, 0, 0}};
            double resolution{0.02};

            std::size_t cells() const
            {
                return static_cast<std::size_t>(size[0]) * size[1] * size[2];
            }
            std::size_t index(int i, int j, int k) const
            {
                return (static_cast<std::size_t>(k) * size[1] + j) * size[0] + i;
            }
            Eigen::Vector3d centre(std::size_t index) const;
            std::array<int, 3> cell(std::size_t index) const;
        };

        /** \brief The work-position method of paper 004 on a two-arm robot model:
            - the work space of each arm: grid cells whose centre the hand reaches with the arm's hand
              orientation (damped-least-squares IK from the neighbouring cells' solutions and from the nearest
              joint-space samples), the arm touching neither the base nor itself (FCL);
            - the common work space: cells both reach, the two arms (at these solutions) not touching each other
              except for the allowed pairs (the two hands meet there);
            - the manipulability area: common cells where the small arm's w = sqrt(det(J J^T)) > threshold;
            - type A (hand-over): the centroid of the common work space, moved to the nearest common cell when it
              is not one;
            - type B (stirring): the common cells from which the whole stirring motion (a horizontal square of
              side stirSide about the cell's centre, drawn by the small hand) keeps w > threshold and is collision
              free, and their centroid (moved to the nearest such cell likewise). */
        class DualArmWorkspace
        {
        public:
            enum Flag : std::uint8_t
            {
                REACH_LARGE = 1,
                REACH_SMALL = 2,
                COMMON = 4,
                AREA = 8,
                STIR = 16
            };

            /** \param home a full configuration (the values of joints outside the two arms, and the arms'
                rest pose) */
            DualArmWorkspace(validity::RobotModelPtr model, ArmTask large, ArmTask small, std::vector<double> home,
                             DualArmSettings settings);

            /** \brief Run the whole analysis (grid, work spaces, area, type A and B). */
            void compute();

            const WorkspaceGrid &grid() const
            {
                return grid_;
            }
            const std::vector<std::uint8_t> &flags() const
            {
                return flags_;
            }
            /** \brief The small arm's w at each cell it reaches (0 elsewhere). */
            const std::vector<float> &smallManipulability() const
            {
                return smallW_;
            }
            std::size_t count(Flag flag) const;
            double volume(Flag flag) const;

            const Eigen::Vector3d &typeACentroid() const
            {
                return centroidA_;
            }
            const Eigen::Vector3d &typeAPosition() const
            {
                return positionA_;
            }
            const Eigen::Vector3d &typeBCentroid() const
            {
                return centroidB_;
            }
            const Eigen::Vector3d &typeBPosition() const
            {
                return positionB_;
            }
            /** \brief Both arms' hands at the type A / type B position (full configurations). */
            const std::vector<double> &typeAConfiguration() const
            {
                return configA_;
            }
            const std::vector<double> &typeBConfiguration() const
            {
                return configB_;
            }

            /** \brief Solve both arms for hand position \e p (seeded from \e q); true when both reach it with
                their orientations and the configuration is collision free (arms, base, each other). */
            bool solveBoth(const Eigen::Vector3d &p, std::vector<double> &q) const;
            /** \brief Solve one arm for hand position \e p (its values in \e q; the others stay): IK from each of
                \e extraSeeds (the arm's values, in chain order), then from the seedsPerCell constrained samples whose
                hands are nearest to \e p (available after compute()); true when a solution that touches neither
                the base nor the arm itself is found. */
            bool solveArm(const ArmTask &task, const Eigen::Vector3d &p, std::vector<double> &q,
                          const std::vector<std::vector<double>> &extraSeeds = {}) const;
            /** \brief The stirring motion about \e centre from configuration \e q (both hands at the centre). */
            StirringMotion stir(const Eigen::Vector3d &centre, const std::vector<double> &q) const;

            /** \brief Collision checks of a full configuration: an arm against the base and itself, and the two
                arms against each other. */
            bool armFree(const ArmTask &task, const std::vector<double> &q) const;
            bool armsApart(const std::vector<double> &q) const;

            const ArmTask &large() const
            {
                return large_;
            }
            const ArmTask &small() const
            {
                return small_;
            }
            const DualArmSettings &settings() const
            {
                return settings_;
            }
            const std::vector<double> &home() const
            {
                return home_;
            }
            const validity::RobotModelPtr &model() const
            {
                return model_;
            }
            /** \brief Seconds spent by compute() in each phase. */
            double workspaceSeconds() const
            {
                return workspaceSeconds_;
            }
            double stirSeconds() const
            {
                return stirSeconds_;
            }

        private:
            void sampleSeeds(const ArmTask &task, std::vector<std::vector<double>> &seeds,
                             std::vector<Eigen::Vector3d> &tips) const;
            std::vector<std::size_t> nearestSeeds(const ArmTask &task, const Eigen::Vector3d &p) const;
            bool moveToNearest(std::uint8_t flag, const Eigen::Vector3d &centroid, Eigen::Vector3d &position,
                               std::size_t &cell) const;

            validity::RobotModelPtr model_;
            ArmTask large_, small_;
            std::vector<double> home_;
            DualArmSettings settings_;
            struct Collision;  ///< FCL objects of the robot's links and the pairs each check tests
            std::shared_ptr<const Collision> collision_;
            std::vector<std::vector<double>> largeSeeds_, smallSeeds_;
            std::vector<Eigen::Vector3d> largeTips_, smallTips_;

            WorkspaceGrid grid_;
            std::vector<std::uint8_t> flags_;
            std::vector<float> smallW_;
            std::vector<std::vector<double>> configs_;  ///< per cell: both arms' solution (common cells)
            Eigen::Vector3d centroidA_{Eigen::Vector3d::Zero()}, positionA_{Eigen::Vector3d::Zero()};
            Eigen::Vector3d centroidB_{Eigen::Vector3d::Zero()}, positionB_{Eigen::Vector3d::Zero()};
            std::vector<double> configA_, configB_;
            double workspaceSeconds_{0.}, stirSeconds_{0.};
        };
    }  // namespace planners
}  // namespace michi

#endif
