#pragma once
// The MPI module's interface (libglint_mpi.so, loaded by module.h only in a process started by
// mpirun): Open MPI and its libraries (PMIx, hwloc, libevent, UCX, ...) stay out of every other
// process. Both sides come from the same build (kMpiModuleAbi), so C++ types cross.
#include "glint/render/distributed.h"

namespace glint {

inline constexpr int kMpiModuleAbi = 1;

struct MpiModule {
    int abi;
    /// MPI_Init_thread (MPI_THREAD_FUNNELED) and a transport over MPI_COMM_WORLD; deleting it
    /// calls MPI_Finalize. Throws IoError if MPI cannot start.
    Transport* (*create)(int* argc, char*** argv);
};

}  // namespace glint

extern "C" const glint::MpiModule* glint_mpi_module();
