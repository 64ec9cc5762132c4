#include "study/cluster.hpp"

#include <cstdlib>

#ifdef ASHLAR_WITH_MPI
#include <mpi.h>
#endif
#ifdef __SANITIZE_ADDRESS__
#include <sanitizer/lsan_interface.h>
#endif

namespace ashlar::cluster {

namespace {

// Open MPI keeps for the life of the process much of what MPI_Init_thread
// and MPI_Finalize allocate. Under AddressSanitizer those allocations are
// left out of the leak check at exit (on the calling thread: what Open
// MPI's progress thread allocates is still checked, tests/sanitizer/
// lsan_mpi.supp). Matching thousands of them against suppressions made
// LeakSanitizer re-read the process's mappings at each frame in a component
// Open MPI had unloaded: 6 s of CPU per rank.
#ifdef __SANITIZE_ADDRESS__
using ThirdPartyAllocations = __lsan::ScopedDisabler;
#else
struct ThirdPartyAllocations {};
#endif

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
  {
    [[maybe_unused]] ThirdPartyAllocations kept_by_open_mpi;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  }
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
  if (g_joined) {
    [[maybe_unused]] ThirdPartyAllocations kept_by_open_mpi;
    MPI_Finalize();
  }
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
