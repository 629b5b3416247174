// libFuzzer target for the VM: the input bytes choose the memory sizes, the
// bytecode image and a stream of commands (tests/vm/fuzz_driver.hpp). Any
// sanitizer report or broken invariant aborts with the input saved.
// Built and run by scripts/fuzz.sh (clang -fsanitize=fuzzer,address,undefined).

#include <cstdio>
#include <cstdlib>

#include "tests/vm/fuzz_driver.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    vm_tests::FuzzCase fuzz_case = vm_tests::fuzz_case_from_bytes(data, size);
    std::string problem = vm_tests::run_fuzz_case(fuzz_case);
    if (!problem.empty()) {
        std::fprintf(stderr, "broken invariant: %s\n", problem.c_str());
        std::abort();
    }
    return 0;
}
