// BLAS and LAPACK as the engine calls them directly (the sparse
// factorisation's dense kernels, core/cholmod_system.cpp, and the split
// factorisation's Schur complement, core/split_cholesky.cpp), and the
// settings of theirs the engine makes.
//
// Fortran interfaces: every argument by pointer, matrices column-major
// with their leading dimension, and the hidden lengths of the character
// arguments last (1 each). Whichever BLAS the build links (OpenBLAS on
// Debian through libblas.so.3) provides them.
#pragma once

#include <cstddef>

extern "C" {
// C = alpha A A^T + beta C (or A^T A), one triangle of C.
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc, size_t uplo_length, size_t trans_length);
// C = alpha op(A) op(B) + beta C.
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, size_t transa_length, size_t transb_length);
// B = alpha op(A)^-1 B (or B op(A)^-1), A triangular.
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, size_t side_length,
            size_t uplo_length, size_t transa_length, size_t diag_length);
// A = U U^T (or L^T L) in place, A triangular.
void dlauum_(const char* uplo, const int* n, double* a, const int* lda, int* info, size_t uplo_length);
// Dense Cholesky factorisation in place, and the solve with its factor.
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info, size_t uplo_length);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda, double* b,
             const int* ldb, int* info, size_t uplo_length);
}

namespace ashlar {

// Sets up OpenBLAS, once, for the WHOLE PROCESS: every BLAS call of every
// library in it from then on, not only the engine's. In the `ashlar` host
// that is the engine's own choice; in a host program that loads the C
// module for stock lua5.4 (or links the engine) it changes that program's
// BLAS too, for as long as it runs. Nothing happens when the loaded BLAS is
// not OpenBLAS. Called by the `ashlar` host first thing, before it starts a
// thread, and otherwise (the C module, the tests) by
// SparseCholesky::factorize (core/sparse_cholesky.hpp), before the first
// factorisation, and by analyze_cra (analysis/cra.hpp) and the FEA's
// contact program (fea/contact_program.hpp) before IPOPT's, whose MUMPS
// runs on the same BLAS. Safe to call from several threads at once; but the
// first call sets and unsets OPENBLAS_CORETYPE (when it changes the
// kernels), which races with a getenv on another thread: a program that
// embeds the engine and reads its environment on other threads calls this
// before it starts them. Two settings:
//
// One thread. Measured on a 2-core machine (22 factorisations of a
// 10,051-block wall's 60,300-row normal matrix): one thread, 3.13 s of
// factorisation and 0.25 s of system time for the whole run; OpenBLAS on 2
// threads 2.85 s, but its idle thread yields the core in a loop between
// calls (6.2 s of system time). On a 100,052-block vault (5.4e10 flops per
// factorisation) two OpenBLAS threads cut the factorisations from 46.6 s
// to 37.3 s, but the idle one yielded for 32 s of system time (40 % of
// user time), so one thread there too. Two cores help where the work
// itself is split: the solver's loops (ParallelLoop) and a large pattern's
// two halves, factored side by side (core/split_cholesky.hpp, 1.7x on that
// wall's factorisations).
//
// Kernels for the CPU. OpenBLAS picks its kernels by CPU model, and
// Debian 12's (0.3.21) does not know the models made after it: on a Xeon
// of family 6, model 207 (AVX2 and AVX-512) it falls back to "Prescott",
// its generic SSE3 kernels. There, unless OPENBLAS_CORETYPE names kernels
// (the user's choice stands), the kernels for the CPU's instruction set
// are taken instead: "SkylakeX" with AVX-512, "Haswell" with AVX2 and FMA,
// as OpenBLAS itself does when told OPENBLAS_CORETYPE. On that machine,
// 10,051-block wall in 3D: user time 11.4 s -> 7.5 s, the same objective
// to 12 digits.
//
// Set here so that a user never needs OPENBLAS_* variables for speed.
void set_up_blas_in_whole_process();

// The workspace of MUMPS, IPOPT's sparse factorisation on these kernels,
// as a percentage above MUMPS's own estimate: IPOPT's mumps_mem_percent in
// both IPOPT programs (analysis/cra.cpp, fea/contact_program.cpp), in place
// of IPOPT's 1000. MUMPS clears its whole workspace at every factorisation:
// on the Armadillo vault (CRA, 231 iterations) eleven times the estimate
// took 108 s, 23 s of them system time for 3.2 million page faults, and
// 30 % takes 66 s (0.5 s, 41,000 faults) with the same iterates to the
// last digit; 50 % 74 s; 20 % 86 s, MUMPS short of room and compressing
// its stack. A factorisation that needs more is retried by IPOPT with
// twice the room.
inline constexpr int kMumpsWorkspacePercent = 30;

}  // namespace ashlar
