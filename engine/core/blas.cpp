#include "core/blas.hpp"

#include <dlfcn.h>

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

}  // namespace

void use_one_blas_thread_in_whole_process() {
  using SetInt = void(int);
  static std::once_flag blas_once;
  std::call_once(blas_once, [] {
    for (const char* library : {"libblas.so.3", "libopenblas.so.0"}) {
      if (SetInt* set_threads = loaded_function<SetInt>(library, "openblas_set_num_threads")) {
        set_threads(1);
      }
    }
  });
}

}  // namespace ashlar
