#include "mpi_team.h"

#include <algorithm>
#include <cstdlib>
#include <string>

// The C API only: Open MPI's deprecated C++ bindings would need a library we do not link.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>

namespace ladarsim::apps {

std::unique_ptr<MpiTeam> MpiTeam::from_environment(int* argc, char*** argv) {
    // Open MPI's launcher sets OMPI_COMM_WORLD_SIZE; PMI-based launchers (Slurm, MPICH) PMI_SIZE.
    if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMI_SIZE")) return nullptr;
    std::unique_ptr<MpiTeam> team(new MpiTeam());
    MPI_Init(argc, argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &team->rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &team->size_);
    if (const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) team->local_size_ = std::max(1, std::atoi(local));
    return team;
}

MpiTeam::~MpiTeam() { MPI_Finalize(); }

bool MpiTeam::any(bool mine) {
    int in = mine ? 1 : 0, out = 0;
    MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
    return out != 0;
}

}  // namespace ladarsim::apps
