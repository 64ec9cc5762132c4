#include "study/cluster.hpp"

#include <cstdlib>

#ifdef ASHLAR_WITH_MPI
#include <mpi.h>
#endif

namespace ashlar::cluster {

namespace {

bool g_joined = false;
int g_rank = 0;
int g_size = 1;

bool launched_by_mpi() {
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(variable) != nullptr) return true;
  return false;
}

}  // namespace

bool built_with_mpi() {
#ifdef ASHLAR_WITH_MPI
  return true;
#else
  return false;
#endif
}

std::string join_if_launched(int* argc, char*** argv) {
  if (g_joined || !launched_by_mpi()) return "";
#ifdef ASHLAR_WITH_MPI
  // Only the thread that coordinates a study calls MPI.
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  g_joined = true;
  return "";
#else
  (void)argc;
  (void)argv;
  return "started by an MPI launcher, but this ashlar was built without MPI: every process runs the whole script";
#endif
}

void leave() {
#ifdef ASHLAR_WITH_MPI
  if (g_joined) MPI_Finalize();
#endif
  g_joined = false;
  g_rank = 0;
  g_size = 1;
}

void abort_job(int exit_code) {
#ifdef ASHLAR_WITH_MPI
  if (g_joined && g_size > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
#else
  (void)exit_code;
#endif
}

int rank() { return g_rank; }
int size() { return g_size; }

}  // namespace ashlar::cluster
