// The entry functions of the fuzz targets (tests/fuzz/README.md): each takes arbitrary bytes,
// runs them through the same code the `oceanref` program runs on such input, and returns
// normally on success or on a clean validation error. Anything else — an exception that is not
// a validation error (a PreconditionError or other std::logic_error, std::bad_alloc, an escaped
// nlohmann::json exception), or a sanitizer report — is a finding: the entry prints the input's
// target and the exception and calls std::abort(), which libFuzzer records as a crash and the
// regression replay (replay.cpp) as a failed test.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace oceanref::fuzz {

// A scene file: the bytes are written to a temporary file and loaded with load_scene (parse and
// validate, as `oceanref render`/`fields` do before realizing anything).
void scene_entry(const std::uint8_t* data, std::size_t size);
// The command line: the bytes split at '\n' and '\0' into arguments after `oceanref`, parsed and
// run for the subcommands that only parse, validate and compute small tables (spectrum, sky,
// brdf). Arguments that would write a file (sky -o/--output, --size) make the input a no-op.
void cli_entry(const std::uint8_t* data, std::size_t size);
// An EXR file as `oceanref compare` reads it: read_parts_for_compare (and read_exr) on the bytes
// written to a temporary file, then the file compared with itself. The readers' memory limit is
// kMaxFuzzPixelBytes, so that a header claiming a huge image is a clean error (as it is for
// `compare --max-memory`), and each input stays fast.
void exr_entry(const std::uint8_t* data, std::size_t size);

// A render piece as `oceanref merge` reads it (read_render_piece on the bytes written to a
// temporary file).
void piece_entry(const std::uint8_t* data, std::size_t size);

// An OBJ mesh (load_obj on the bytes written to a temporary file, at the default limits). An
// ObjError is the clean outcome for bad input; a PreconditionError — the validator and
// tinyobjloader reading a file differently — is a finding.
void obj_entry(const std::uint8_t* data, std::size_t size);

inline constexpr double kMaxFuzzPixelBytes = 16.0 * 1024 * 1024;

// The entry of a target by name ("scene", "cli", "exr", "piece", "obj"); nullptr for another
// name.
using Entry = void (*)(const std::uint8_t*, std::size_t);
Entry entry_for(std::string_view target);

}  // namespace oceanref::fuzz
