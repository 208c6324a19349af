// The per-call engine comparison (engine_kernels.cpp): the general-normal engine-convention
// headers (planar_engine, noncentral_3d_engine: 1/m and I^{-1} as inputs, the normal the n
// axis of the contact frame) called one impact at a time, checked and _unchecked, against a
// hand-written engine formula specialised the same way (the same normal as a constant, the
// same inputs, the same result struct). One set per compiler, as for the batch kernels:
// built by the project's compiler and by the other of g++ and clang++, in one process.
#pragma once

extern "C" {

/// One loop over n impacts, rows of inputs (in + i * stride), one call per impact, each
/// result written to *out (a result struct of the header) and fenced so that no loop is
/// vectorised across calls (the calls stay calls, as in an engine's contact loop). When
/// impulses is not null, the normal impulse of impact i is copied to impulses[i] (the
/// cross-check between the variants; null when timed, so that the loop never reads a
/// result back).
typedef void (*impactgen_engine_kernel)(long n, const double* in, long stride, void* out, double* impulses);

struct impactgen_engine_kernel_set {
    const char* id;       ///< the compiler family, in the benchmarks' names: gcc, clang
    const char* compiler; ///< e.g. "g++ 12.2.0", "clang++ 14.0.6"
    impactgen_engine_kernel planar_checked, planar_unchecked, planar_hand;
    impactgen_engine_kernel noncentral_checked, noncentral_unchecked, noncentral_hand;
};

const impactgen_engine_kernel_set* impactgen_engine_kernels_main();
const impactgen_engine_kernel_set* impactgen_engine_kernels_other();
}
