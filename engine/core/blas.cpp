#include "core/blas.hpp"

#include <dlfcn.h>
#include <strings.h>

#include <cstdlib>
#include <mutex>

namespace ashlar {

namespace {

// A function of a shared library this process has already loaded (its
// BLAS), or null. Looked up by handle, not in the global scope: in the C
// module for stock lua5.4 it is loaded RTLD_LOCAL.
template <typename Function>
Function* loaded_function(const char* library, const char* name) {
  void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD);
  if (!handle) return nullptr;
  void* symbol = dlsym(handle, name);
  dlclose(handle);  // only drops the reference RTLD_NOLOAD took
  return reinterpret_cast<Function*>(symbol);
}

// The OpenBLAS kernels for this CPU's instruction set when OpenBLAS fell
// back to its generic ones (blas.hpp says why), through its own way of
// choosing them: OPENBLAS_CORETYPE, read when its kernel table is set up
// again. The variable is set only for that call; a user's stands.
void use_kernels_for_the_cpu(const char* library) {
  using Name = char*();
  using Call = void();
  Name* core_name = loaded_function<Name>(library, "openblas_get_corename");
  Call* forget_kernels = loaded_function<Call>(library, "gotoblas_dynamic_quit");
  Call* choose_kernels = loaded_function<Call>(library, "gotoblas_dynamic_init");
  if (!core_name || !forget_kernels || !choose_kernels || std::getenv("OPENBLAS_CORETYPE")) return;
  if (strcasecmp(core_name(), "Prescott") != 0) return;
  __builtin_cpu_init();
  const char* kernels = nullptr;
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
      __builtin_cpu_supports("avx512cd")) {
    kernels = "SkylakeX";
  } else if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    kernels = "Haswell";
  }
  if (!kernels) return;
  setenv("OPENBLAS_CORETYPE", kernels, 1);
  forget_kernels();
  choose_kernels();
  unsetenv("OPENBLAS_CORETYPE");
}

}  // namespace

void set_up_blas_in_whole_process() {
  using SetInt = void(int);
  static std::once_flag blas_once;
  std::call_once(blas_once, [] {
    // libblas.so.3 is OpenBLAS itself or a thin library over
    // libopenblas.so.0 (Debian's alternatives): the first that has the
    // functions is the one.
    for (const char* library : {"libblas.so.3", "libopenblas.so.0"}) {
      if (SetInt* set_threads = loaded_function<SetInt>(library, "openblas_set_num_threads")) {
        set_threads(1);
        use_kernels_for_the_cpu(library);
        break;
      }
    }
  });
}

}  // namespace ashlar
