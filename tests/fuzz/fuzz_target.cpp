// One libFuzzer target (built once per entry, OCEANREF_FUZZ_ENTRY = scene_entry, cli_entry or
// exr_entry): tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>

#include "core/fp_environment.h"
#include "fuzz_entries.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const oceanref::ReferenceFpEnvironment fp;
  oceanref::fuzz::OCEANREF_FUZZ_ENTRY(data, size);
  return 0;
}
