#pragma once
// A render's processes when mpirun launched it: the MPI ranks as a FrameTeam.
#include <memory>

#include "ladarsim/sensor_model/render/render_dataset.h"

namespace ladarsim::apps {

class MpiTeam : public sensor_model::FrameTeam {
public:
    /// The team of this mpirun job; null when the process was not launched by mpirun, so that the
    /// same binary runs as one process without MPI starting at all.
    static std::unique_ptr<MpiTeam> from_environment(int* argc, char*** argv);
    ~MpiTeam() override;
    MpiTeam(const MpiTeam&) = delete;
    MpiTeam& operator=(const MpiTeam&) = delete;

    int rank() const override { return rank_; }
    int size() const override { return size_; }
    bool any(bool mine) override;
    /// Processes of this job on this machine (they share its cores).
    int local_size() const { return local_size_; }

private:
    MpiTeam() = default;
    int rank_ = 0;
    int size_ = 1;
    int local_size_ = 1;
};

}  // namespace ladarsim::apps
