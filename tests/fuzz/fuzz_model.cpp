// libFuzzer entry point for the model artifact. An input that does not start
// like an artifact is taken as an artifact's body and given a valid checksum,
// so the fuzzer reaches the fields and validation rather than stopping at the
// checksum. Any input must end in a ReadError or a model that the runtime's
// init() accepts (or that exceeds the host capacity) and streams with labels
// in range: anything else (crash, sanitizer report, hang, other exception,
// an out-of-range label, NaN) is a bug.
#include <cinttypes>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "run/state.hpp"
#include "model/artifact.hpp"
#include "io/clip.hpp"
#include "model/header.hpp"
#include "fuzz_frames.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

// The body under the current version, or (when the input's length is odd)
// under the previous one, whose GMM factors are read component by component
// and reordered: both readers are fuzzed.
std::string with_checksum(const std::string& body) {
    char line[64];
    std::snprintf(line, sizeof line, "checksum fnv1a64 %016" PRIx64 "\n", fnv1a64(body));
    const int version = body.size() % 2 == 1 ? artifact_version - 1 : artifact_version;
    return "actionstring-model " + std::to_string(version) + "\n" + line + body;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    if (text.rfind("actionstring-model", 0) != 0) text = with_checksum(text);
    ModelData model;
    try {
        model = parse_model("fuzz.model", text);
    } catch (const ReadError&) {
        return 0;  // the expected outcome for malformed input
    }
    // A model that loads has passed the same checks as codegen and init().
    const std::string header = generate_header(model, "0", "fuzz", "fuzz.model");
    if (header.empty()) std::abort();
    fuzz::stream_and_check(model.view());
    return 0;
}
