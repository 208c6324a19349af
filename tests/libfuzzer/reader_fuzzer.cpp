// libFuzzer target over the problem reader and everything a problem file
// reaches: read_problem, derive, solve, the answer and formula printers. Any
// input must end in a problem or an input_error; a crash, a sanitizer report,
// an uncaught exception or a hang is a finding.
//
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DIMPACTGEN_LIBFUZZER=ON
//   cmake --build build-fuzz --target reader_fuzzer
//   build-fuzz/tests/libfuzzer/reader_fuzzer -max_total_time=600 -timeout=10 tests/libfuzzer/corpus
#include "print/answer.hpp"
#include "print/formulas.hpp"
#include "symbolic/solution.hpp"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        impactgen::problem p = impactgen::read_problem(text, "fuzz.json");
        impactgen::derivation d = impactgen::derive(p);
        impactgen::solution s = impactgen::solve(d);
        if (p.is_numeric())
            (void)impactgen::print::answer_json(d, s, false).dump();
        else
            (void)impactgen::print::formulas_text(d, s);
    } catch (const impactgen::input_error&) {
        // a refusal with a message: the expected end of bad input
    }
    return 0;
}
