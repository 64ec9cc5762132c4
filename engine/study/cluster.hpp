// The MPI job this process belongs to, when it was started by mpirun (or
// srun): rank 0 coordinates studies, the other ranks run rows. An optional
// build feature (ASHLAR_WITH_MPI); without it, or when not launched by an
// MPI launcher, the process is rank 0 of 1 and nothing here talks to MPI.
#pragma once

#include <string>

namespace ashlar::cluster {

// Whether this build can join MPI jobs.
bool built_with_mpi();

// Joins the MPI job when the environment says an MPI launcher started this
// process (OMPI_COMM_WORLD_SIZE, PMI_SIZE or PMIX_RANK are set). Returns a
// warning when launched by one but built without MPI, else "".
std::string join_if_launched(int* argc, char*** argv);

// Leaves the job (MPI_Finalize) if joined; a no-op otherwise.
void leave();

// Ends every process of the job with this exit code (a rank that fails
// alone would leave the others waiting); returns when not in a job.
void abort_job(int exit_code);

int rank();  // 0 when not in a job
int size();  // 1 when not in a job

}  // namespace ashlar::cluster
